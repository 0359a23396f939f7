#!/usr/bin/env bash
# Prepare a machine for rfc: GHDL (with its llvm back-end), Yosys, Tcl, g++, make and Perl from
# the system package manager when missing, and .venv holding rfc with its development extras.
# Idempotent; quick when done.
# Usage: tools/setup.sh   (sourced or run; prints nothing when there is nothing to do)
set -euo pipefail

rfc_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

install_simulators() {
    local missing=()
    command -v ghdl >/dev/null 2>&1 || missing+=(ghdl)
    # GHDL's llvm back-end compiles the logic `rfc sim` runs to a native program: about twice
    # as fast as the mcode one Debian's ghdl brings (docs/performance.md).
    command -v ghdl-llvm >/dev/null 2>&1 || missing+=(ghdl-llvm)
    # The tests run mcode (tests/conftest.py): the suite analyzes hundreds of logics once each,
    # where llvm's compile of each costs seconds to minutes. apt satisfies ghdl with whichever
    # back-end comes in the same install, so mcode is asked for by name.
    command -v ghdl-mcode >/dev/null 2>&1 || missing+=(ghdl-mcode)
    command -v yosys >/dev/null 2>&1 || missing+=(yosys)
    # tclsh runs the generated Vivado/Vitis scripts under recording stand-ins in the tests.
    command -v tclsh >/dev/null 2>&1 || missing+=(tcl)
    # Verilator's models and rfc's HLS C-simulation are compiled with g++ and make; Verilator's
    # driver script is Perl.
    command -v g++ >/dev/null 2>&1 || missing+=(g++)
    command -v make >/dev/null 2>&1 || missing+=(make)
    command -v perl >/dev/null 2>&1 || missing+=(perl)
    [ ${#missing[@]} -eq 0 ] && return 0
    local cmd="apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y ${missing[*]}"
    echo "rfc set-up: installing ${missing[*]}" >&2
    if [ "$(id -u)" -eq 0 ]; then
        bash -c "$cmd" >&2
    elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
        sudo bash -c "$cmd" >&2
    else
        echo "rfc set-up: ${missing[*]} missing and this user cannot install packages; run:" >&2
        echo "    sudo bash -c '$cmd'" >&2
        exit 1
    fi
}

install_venv() {
    local venv="$rfc_root/.venv"
    local python=${PYTHON:-python3}
    if [ ! -x "$venv/bin/python" ]; then
        echo "rfc set-up: creating $venv" >&2
        "$python" -m venv "$venv"
    fi
    # Reinstall only when the project's metadata changed since the last install.
    local stamp="$venv/.rfc-setup-stamp"
    local want
    want=$(cat "$rfc_root/pyproject.toml" | sha256sum | cut -c1-32)
    if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
        echo "rfc set-up: installing rfc and its development extras into $venv" >&2
        "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
            -e "$rfc_root[dev]" 2> >(grep -v "is ignored: it is neither a file nor a directory" >&2)
        echo "$want" >"$stamp"
    fi
}

install_simulators
install_venv
