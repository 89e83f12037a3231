#!/usr/bin/env bash
# Install Pinocchio's C++ library (the `pin` wheel with Eigen's and urdfdom's headers) into a venv
# at ~/.cache/osrl-pin-venv, where `osrl bench references` looks for it (or set OSRL_PIN_PYTHON to
# a Python that has it). A few minutes, ~300 MB; only the dynamics benchmark needs it.
set -euo pipefail
venv=${1:-$HOME/.cache/osrl-pin-venv}
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet pin==4.1.0 cmeel-eigen cmeel-urdfdom-headers
"$venv/bin/python" -c "import pinocchio; print('pin', pinocchio.__version__, 'in $venv')"
