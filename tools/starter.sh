#!/bin/sh
# tools/starter.sh DIR [--solved] [--with-wings] -- writes the student kit, DIR/rt-starter and
# DIR/rt-starter.tar.gz (`make starter`): rt's teaching core and app/ as given code, with the
# functions tools/starter/stubs.list names replaced by stubs (tools/starter/stubs.txt), and without
# the robust/ and fast/ wings: the regions of the sources marked `// starter: begin NAME` ...
# `// starter: end` (tools/starter/regions.awk). The kit is made from the very code rt tests.
# --solved keeps rt's bodies in place of the stubs (the kit's checks must then all pass).
# --with-wings keeps robust/ and fast/ (for a teacher who asks for them): the kit then runs rt's
# robust methods by default, and the handouts' under --methods handout.
set -eu
out=$1
shift
solved=0 wings=0
for option in "$@"; do
    case $option in
    --solved) solved=1 ;;
    --with-wings) wings=1 ;;
    *) echo "tools/starter.sh: unknown option $option" >&2 && exit 2 ;;
    esac
done
kit=$out/rt-starter
stubs=" $(sed 's/#.*//' tools/starter/stubs.list | tr -s ' \t\n' '   ') "
for name in $stubs; do
    grep -q "^@@ $name\$" tools/starter/stubs.txt ||
        { echo "tools/starter/stubs.list: no stub named $name (tools/starter/stubs.txt)" >&2 && exit 2; }
done
rm -rf "$kit"
mkdir -p "$kit/app" "$kit/tests" "$kit/scenes"
region() {
    awk -v stubs="$stubs" -v solved=$solved -v wings=$wings -f tools/starter/regions.awk \
        tools/starter/stubs.txt "$1" >"$kit/$1"
}
for file in ray.h ray.cpp camera.cpp blur.cpp geometry.cpp shade.cpp smooth.cpp render.cpp render.h \
    path.cpp path_sampling.h numbers.h scene_*.cpp app/*.h app/*.cpp tests/test.h \
    tests/test_handout.cpp tests/kit_main.cpp; do
    region "$file"
done
if [ $wings = 1 ]; then
    mkdir -p "$kit/robust" "$kit/fast"
    cp robust/*.cpp robust/*.h "$kit/robust/" && cp fast/*.cpp fast/*.h "$kit/fast/"
fi
cp scenes/*.scene scenes/*.obj "$kit/scenes/"
cp tools/starter/Makefile tools/starter/README.md tools/starter/stubs.list .clang-format LICENSE "$kit/"
(cd "$out" && tar czf rt-starter.tar.gz rt-starter)
echo "$kit/ and $out/rt-starter.tar.gz: the kit, with stubs for:$stubs"
