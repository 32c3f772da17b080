#!/bin/sh
# Runs the whole twinray bench on this machine's GPU with only what this folder brings:
# the release build (both shader sets are inside it), the Vulkan loader and the GL dispatch
# libraries that the NVIDIA driver's Vulkan ICD loads. No network and no install needed;
# the NVIDIA driver itself must be there. Everything lands in one folder (default: report/
# beside this script); the references are cached in cache/ beside it.
#
#   [WIDTH=W HEIGHT=H] [SPP=LIST] [IMAGES=all|last|none] sh run.sh [REPORT_DIR] [extra twinray bench arguments...]
#
# Every scene renders at 1920x1080 unless WIDTH and HEIGHT say otherwise: on a GPU a smaller
# trace is mostly launch overhead. SPP (default 1,4,16,64) is the pixel sample counts, IMAGES
# (default last) which renders are kept as PNG files.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
report=${1:-"$here/report"}
[ $# -gt 0 ] && shift
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
bin="$here/bin/twinray"
mkdir -p "$report"

bench="$bin bench --width ${WIDTH:-1920} --height ${HEIGHT:-1080} --runs 10 --warmup 3 --spp ${SPP:-1,4,16,64} --reference-spp 1024 --shadow-spp 1,4,16,64,256 \
--probes $here/probes/stability --timing-rays 4194304 --images ${IMAGES:-last} --cache $here/cache --out $report $*"
stability="$bin stability --dir $here/probes/stability --runs 10 --warmup 2 --timing-rays 4194304"

"$bin" info > "$report/device.txt"
$bench
$stability > "$report/stability.txt" || true   # exit 1 means a missed target: it is in the table
{
    echo "# How this report was made"
    echo
    echo "Device (twinray info):"
    echo
    sed 's/^/    /' "$report/device.txt"
    echo
    echo "Commands (run.sh from \`cargo xtask bundle\`, twinray $("$bin" --version | cut -d' ' -f2)):"
    echo
    echo "    $bench" | sed "s|$here|BUNDLE|g; s|$report|REPORT|g"
    echo "    $stability > REPORT/stability.txt" | sed "s|$here|BUNDLE|g"
} > "$report/COMMANDS.md"
echo "report in $report"
