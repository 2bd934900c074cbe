#!/bin/sh
# Builds the grader from the kit in this bundle, and compiles the kit's own files once, so that a
# submission compiles only the files its student changed. Run by setup.sh (or by hand, to try
# the bundle on another machine: then run_autograder with AUTOGRADER_ROOT set). OPT: the
# optimisation a submission is compiled with (-O2).
set -e
cd "$(dirname "$0")"
echo "${OPT:--O2} -std=c++17 -w -ffp-contract=off -fno-math-errno -pthread $(pkg-config --cflags libpng 2>/dev/null)" >cxxflags
echo "$(pkg-config --libs libpng 2>/dev/null || echo -lpng) -pthread" >libs
(cd kit && MAKEFLAGS= make CXX="${CXX:-g++}" build/grader >/dev/null)
cp kit/build/grader grader
mkdir -p objects
./grader set --submission kit --kit kit --objects objects --cxx "${CXX:-g++}" \
    --cxxflags "$(cat cxxflags)" --libs "$(cat libs)" >/dev/null || true
