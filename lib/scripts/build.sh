#!/usr/bin/env bash
# rfc: build this system for the board — every HLS accelerator with Vitis HLS, then the
# Vivado project, block design, bitstream and hardware export (vivado/<project>.xsa).
# Needs vitis_hls (when there are HLS accelerators) and vivado on PATH (AMD/Xilinx 2022.1+).
set -euo pipefail
cd "$(dirname "$0")"

need() {
    if ! command -v "$1" >/dev/null 2>&1; then
        echo "build.sh: '$1' is not on PATH; source the Vivado/Vitis settings64.sh first" >&2
        exit 1
    fi
}

runs=(hls/*/run.tcl)
if [ -e "${runs[0]}" ]; then
    need vitis_hls
    for run in "${runs[@]}"; do
        echo "build.sh: HLS synthesis of $(dirname "$run")"
        vitis_hls -f "$run"
    done
fi
need vivado
vivado -mode batch -nojournal -log vivado/build.log -source vivado/build.tcl
echo "build.sh: bitstream and hardware export in vivado/"
