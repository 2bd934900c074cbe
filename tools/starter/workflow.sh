#!/bin/sh
# tools/starter/workflow.sh SET -- prints the kit's GitHub Classroom workflow
# (.github/workflows/classroom.yml): on each push, GitHub builds the kit and runs its checks
# (`make test`) and the grader, one test a grading scene of SET (`make grade SCENE=NAME`), each
# a GitHub Classroom command grader worth 1 point, and reports them with Classroom's reporter.
set -eu
scenes=$(sed 's/ .*//' "$1/scenes.txt")
cat <<'YAML'
# GitHub Classroom runs this on every push: it builds the kit, runs its checks (make test) and
# grades ./ray on each grading scene (make grade SCENE=NAME), a point a scene.
name: Autograding Tests
'on':
  - push
  - repository_dispatch
permissions:
  checks: write
  actions: read
  contents: read
jobs:
  run-autograding-tests:
    runs-on: ubuntu-latest
    if: github.actor != 'github-classroom[bot]'
    steps:
      - name: Checkout code
        uses: actions/checkout@v4
      - name: Install the compiler and libpng
        run: sudo apt-get update && sudo apt-get install -y g++ make libpng-dev pkg-config
      - name: Build
        run: make
      - name: checks
        id: checks
        uses: classroom-resources/autograding-command-grader@v1
        with:
          test-name: checks
          command: make test
          timeout: 10
          max-score: 1
YAML
for scene in $scenes; do
    cat <<YAML
      - name: scene $scene
        id: scene-$scene
        uses: classroom-resources/autograding-command-grader@v1
        with:
          test-name: $scene
          command: make grade SCENE=$scene
          timeout: 5
          max-score: 1
YAML
done
printf '      - name: Autograding Reporter\n        uses: classroom-resources/autograding-grading-reporter@v1\n        env:\n'
printf '          CHECKS_RESULTS: "${{steps.checks.outputs.result}}"\n'
runners=checks
for scene in $scenes; do
    upper=$(printf 'SCENE-%s' "$scene" | tr 'a-z_' 'A-Z_')
    printf '          %s_RESULTS: "${{steps.scene-%s.outputs.result}}"\n' "$upper" "$scene"
    runners=$runners,scene-$scene
done
printf '        with:\n          runners: %s\n' "$runners"
