#!/bin/sh
# The README's "Writing a scene in C++", followed to the letter in a copy of the sources: a
# scene_mine.cpp from the README's code block, its declaration in ray.h, its line in ray.cpp,
# `make`, and `./ray mine`. Ends, as every test program does, with `N passed, M failed`: one
# check, that the scene builds, renders, and its mirror sphere is where the code puts it.
set -u
root=$(pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$root"/*.cpp "$root"/*.h "$root"/Makefile "$work"/
for wing in robust fast app tools; do
    mkdir -p "$work/$wing" && cp "$root/$wing"/*.cpp "$work/$wing/"
    cp "$root/$wing"/*.h "$work/$wing/" 2>/dev/null
done
# insert FILE PATTERN LINE: LINE before the first line that matches PATTERN (portable: no sed -i)
insert() {
    awk -v pattern="$2" -v line="$3" '!done && $0 ~ pattern { print line; done = 1 } { print }' \
        "$1" >"$1.new" && mv "$1.new" "$1"
}
follow() {
cd "$work" || return 1
# 1. the README's code block, as scene_mine.cpp
awk '/^```cpp$/ { inside = 1; next } /^```$/ { if (inside) exit } inside' "$root/README.md" >scene_mine.cpp
grep -q "void BuildMyScene" scene_mine.cpp || return 1
# 2. its declaration beside BuildDefaultScene
insert ray.h '^void BuildDefaultScene\(Scene \*scene\);' 'void BuildMyScene(Scene *scene);'
# 3. its line in kBuiltInScenes
insert ray.cpp '^    \{"default", "reference.png", BuildDefaultScene\},' '    {"mine", "mine.png", BuildMyScene},'
grep -q BuildMyScene ray.h && grep -q '"mine"' ray.cpp || return 1
# 4. make && ./ray mine
make -j2 ray CXXFLAGS=-O0 >build.log 2>&1 || { tail -20 build.log; return 1; }
./ray mine --size 32 >/dev/null && test -s mine.png || return 1
./ray mine --ray 0 0 0 0 0 -1 | grep -q '"t":5,' # the mirror sphere of radius 1 at z = -6
}
if follow; then
    echo "1 passed, 0 failed"
else
    echo "tests/recipe.sh: FAILED the README's recipe for a scene in C++ does not build and render"
    echo "0 passed, 1 failed"
fi
