#!/bin/sh
# tools/starter.sh DIR [--solved] -- writes the student kit, DIR/rt-starter and
# DIR/rt-starter.tar.gz (`make starter`): rt's teaching core and app/ as given code, with the
# functions tools/starter/stubs.list names replaced by stubs (tools/starter/stubs.txt), and without
# the robust/ and fast/ wings: the regions of the sources marked `// starter: begin NAME` ...
# `// starter: end` (tools/starter/regions.awk). The kit is made from the very code rt tests.
# --solved keeps rt's bodies in place of the stubs (the kit's checks must then all pass).
set -eu
out=$1
solved=0
[ "${2:-}" = --solved ] && solved=1
kit=$out/rt-starter
stubs=" $(sed 's/#.*//' tools/starter/stubs.list | tr -s ' \t\n' '   ') "
for name in $stubs; do
    grep -q "^@@ $name\$" tools/starter/stubs.txt ||
        { echo "tools/starter/stubs.list: no stub named $name (tools/starter/stubs.txt)" >&2 && exit 2; }
done
rm -rf "$kit"
mkdir -p "$kit/app" "$kit/tests" "$kit/scenes"
region() { awk -v stubs="$stubs" -v solved=$solved -f tools/starter/regions.awk tools/starter/stubs.txt "$1" >"$kit/$1"; }
for file in ray.h ray.cpp camera.cpp geometry.cpp shade.cpp render.cpp render.h path.cpp \
    path_sampling.h numbers.h scene_*.cpp app/*.h app/*.cpp tests/test.h tests/test_handout.cpp \
    tests/kit_main.cpp; do
    region "$file"
done
cp scenes/*.scene scenes/*.obj "$kit/scenes/"
cp tools/starter/Makefile tools/starter/README.md tools/starter/stubs.list .clang-format LICENSE "$kit/"
(cd "$out" && tar czf rt-starter.tar.gz rt-starter)
echo "$kit/ and $out/rt-starter.tar.gz: the kit, with stubs for:$stubs"
