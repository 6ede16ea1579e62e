#!/usr/bin/env bash
# Gradescope autograder image set-up (runs once, when the image is built).
#
# Zip this folder's files together with a checkout of voxlab (the
# instructor's, with reference/) in a folder named voxlab, and, to choose
# the stages, their points and test visibility, a copy of one of voxlab's
# courses/*.json named assignment.json:
#   autograder.zip: setup.sh, run_autograder, assignment.json, voxlab/...
# Gradescope unpacks it into /autograder/source/ and runs this script on its
# base image (Ubuntu 22.04). `tools/setup.sh --grader` installs only what
# grading needs and builds only the voxlab program: no viewer, no tests.
set -euo pipefail
cd "${VOXLAB_AUTOGRADER_ROOT:-/autograder}/source/voxlab"
tools/setup.sh --grader
# The reference's expected outputs, rendered now into the image's cache so
# that each submission's grading renders only the submission's own images
# (run_autograder reads the same folder).
VOXLAB_EXPECTED_CACHE="$PWD/expected_cache" LP_NUM_THREADS=1 build/bin/voxlab grade --prepare --quiet
