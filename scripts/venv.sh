#!/usr/bin/env bash
# The Python of the checks: a virtual environment of the project's own, target/venv (git-ignored;
# OBLIQUE_VENV names another folder), created once with `python3 -m venv` and reused, holding
# h5py, numpy, pytest, matplotlib and mypy (and, installed by scripts/test, the package as its
# portable wheel).
# Nothing is installed into the user's Python: this works where that Python refuses pip
# (Debian 12's /usr/lib/python3.11/EXTERNALLY-MANAGED, PEP 668). On Debian, `python3 -m venv`
# needs the python3-venv package, installed with apt-get (scripts/setup.sh) when it is missing.
#
# Sourced by scripts/test, scripts/check_table.sh and scripts/check_slurm.sh: afterwards the
# environment's bin/ is first on PATH, so `python3` in every later step (the Rust tests that run
# python3 included) is the environment's, and OBLIQUE_VENV is exported. Concurrent callers are
# serialised by a lock beside the folder.
root="${root:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
OBLIQUE_VENV="${OBLIQUE_VENV:-$root/target/venv}"
export OBLIQUE_VENV
# What the checks import: the module names and the pip requirements that provide them.
oblique_venv_modules="h5py, numpy, pytest, matplotlib, mypy"
oblique_venv_packages=(h5py numpy pytest matplotlib mypy)

oblique_venv_ready() {
  [ -x "$OBLIQUE_VENV/bin/python3" ] &&
    "$OBLIQUE_VENV/bin/python3" -c "import $oblique_venv_modules" >/dev/null 2>&1
}

oblique_venv_create() {
  local py
  py="$(command -v python3 || true)"
  if [ -z "$py" ]; then
    echo "venv: no python3 on PATH; install Python 3.9 or newer (Debian: python3, python3-venv)" >&2
    return 1
  fi
  # A folder that is not a working environment (an interrupted creation, a Python upgraded
  # since): made anew.
  rm -rf "$OBLIQUE_VENV"
  echo "venv: creating the checks' Python environment $OBLIQUE_VENV (once; about a minute)" >&2
  if ! "$py" -m venv "$OBLIQUE_VENV" >/dev/null 2>&1; then
    # Debian's python3 lacks ensurepip without python3-venv.
    rm -rf "$OBLIQUE_VENV"
    OBLIQUE_SETUP_EXTRA="python3-venv" source "$root/scripts/setup.sh"
    "$py" -m venv "$OBLIQUE_VENV" || {
      rm -rf "$OBLIQUE_VENV"
      echo "venv: \`$py -m venv $OBLIQUE_VENV\` failed (above)" >&2
      return 1
    }
  fi
}

if ! oblique_venv_ready; then
  mkdir -p "$(dirname "$OBLIQUE_VENV")"
  (
    flock 9
    if ! oblique_venv_ready; then
      if ! "$OBLIQUE_VENV/bin/python3" -m pip --version >/dev/null 2>&1; then
        oblique_venv_create
      fi
      echo "venv: installing ${oblique_venv_packages[*]} into $OBLIQUE_VENV (pip)" >&2
      "$OBLIQUE_VENV/bin/python3" -m pip install --quiet --disable-pip-version-check \
        "${oblique_venv_packages[@]}"
      oblique_venv_ready || {
        echo "venv: $oblique_venv_modules still not importable in $OBLIQUE_VENV" >&2
        exit 1
      }
    fi
  ) 9>"$OBLIQUE_VENV.lock"
fi
case ":$PATH:" in
  *":$OBLIQUE_VENV/bin:"*) ;;
  *) export PATH="$OBLIQUE_VENV/bin:$PATH" ;;
esac
export VIRTUAL_ENV="$OBLIQUE_VENV"
