#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image (Ubuntu): what the
# grader needs, then the grader and the kit's own files compiled (build.sh).
set -e
apt-get update
DEBIAN_FRONTEND=noninteractive apt-get install -y g++ make libpng-dev pkg-config
sh /autograder/source/build.sh
