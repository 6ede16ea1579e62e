#!/usr/bin/env bash
# Gradescope autograder image set-up (runs once, when the image is built).
#
# Zip this folder's two files together with a checkout of voxlab (the
# instructor's, with reference/) in a folder named voxlab:
#   autograder.zip: setup.sh, run_autograder, voxlab/...
# Gradescope unpacks it into /autograder/source/ and runs this script on its
# Ubuntu/Debian image. tools/setup.sh installs the Debian packages and builds.
set -euo pipefail
cd /autograder/source/voxlab
tools/setup.sh
