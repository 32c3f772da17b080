#!/bin/sh
# twinray inspect on the H100 after the probe and explain stages check their buffers before the trace.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
"$here/bin/twinray" inspect --a rust --b glsl --spp 16
