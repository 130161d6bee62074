#!/bin/bash
# Special reliability test: a byte flipped in a finished block
# of a sweep's working file, and a damaged chunk index, are detected when the sweep
# is resumed: exit 2 (or 1), one line on stderr saying the file is damaged, no HDF5
# error stack, and no final file marked complete.
# Env: DPEND (binary), ROOT (repository), SCRATCH (empty directory, the cwd).
# Exit 0 pass, 77 skip (with a note), anything else fail.
set -u
# read the working file while the sweep holds it open (HDF5 locks files by default)
export HDF5_USE_FILE_LOCKING=FALSE
cd "${SCRATCH:-.}" || exit 1
dpend=${DPEND:?DPEND must name the dpend binary}
for tool in h5dump python3; do
    if ! command -v "$tool" >/dev/null 2>&1; then
        echo "corrupt_block: skipped ($tool not found)"
        exit 77
    fi
done
args=(sweep --quiet --n 48 --block 48 --threads 1 --t-end 300 --stop-at end --output s.h5)

# the working file while the sweep runs (its name may differ from the final one)
working_file() {
    local f
    for f in s.h5 s.h5* .s.h5* .*s.h5*; do
        [ -f "$f" ] || continue
        if h5dump -a /sweep/complete "$f" 2>/dev/null | grep -q '(0): 0'; then
            echo "$f"
            return 0
        fi
    done
    return 1
}
done_blocks() { h5dump -d /sweep/done "$1" 2>/dev/null | grep -o '\b1\b' | wc -l; }
is_complete() { h5dump -a /sweep/complete "$1" 2>/dev/null | grep -q '(0): 1'; }

# 1. run the sweep and kill it once at least two blocks are done
"$dpend" "${args[@]}" >/dev/null 2>&1 &
pid=$!
work=
for _ in $(seq 1 600); do
    sleep 0.1
    if work=$(working_file) && [ "$(done_blocks "$work")" -ge 3 ]; then break; fi
    work=
    kill -0 "$pid" 2>/dev/null || break
done
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
[ -n "$work" ] || work=$(working_file) || true
if [ -z "$work" ]; then
    echo "corrupt_block: skipped (the sweep finished or never wrote a block before the kill)"
    exit 77
fi
cp "$work" pristine.bin
workname=$work

# 2. flip one byte in the data of the first finished block (energy0, uncompressed chunk)
block=$(h5dump -d /sweep/done "$work" | tr -s ' ,\n' '\n' | grep -E '^[01]$' | grep -n '^1$' \
    | head -1 | cut -d: -f1)
h5dump -d /sweep/energy0 -s "$((block - 1)),0" -c 1,48 -b LE -o block.bin "$work" >/dev/null 2>&1
python3 - "$work" block.bin <<'PY' || { echo "corrupt_block: FAIL (block bytes not found once)"; exit 1; }
import sys
path, pattern = sys.argv[1], open(sys.argv[2], 'rb').read()
data = bytearray(open(path, 'rb').read())
if len(pattern) != 384 or data.count(pattern) != 1:
    sys.exit(1)
data[data.find(pattern) + 100] ^= 0x10
open(path, 'wb').write(data)
PY
rm -f block.bin

check_refused() {  # WHAT
    local rc lines
    "$dpend" "${args[@]}" >out.txt 2>err.txt
    rc=$?
    lines=$(wc -l < err.txt)
    if [ "$rc" != 2 ] && [ "$rc" != 1 ]; then
        echo "corrupt_block: FAIL ($1: exit $rc, expected 2 or 1: $(head -c 300 err.txt))"
        exit 1
    fi
    if [ "$lines" != 1 ] || grep -q 'HDF5-DIAG\|#0[0-9][0-9]:' err.txt; then
        echo "corrupt_block: FAIL ($1: $lines lines on stderr, expected one without HDF5's stack)"
        exit 1
    fi
    if grep -qE 'Fortran runtime error|Backtrace|Floating point' err.txt; then
        echo "corrupt_block: FAIL ($1: trap)"
        exit 1
    fi
    for f in s.h5 s.h5* .s.h5*; do
        if [ -f "$f" ] && is_complete "$f"; then
            echo "corrupt_block: FAIL ($1: '$f' is marked complete)"
            exit 1
        fi
    done
}

# 3. resume: refused as damaged
check_refused 'flipped byte in a finished block'
if ! grep -qi 'damaged' err.txt; then
    echo "corrupt_block: FAIL (message does not say the file is damaged: $(cat err.txt))"
    exit 1
fi
msg1=$(cat err.txt)

# 4. a damaged chunk index (B-tree node signature), on a fresh copy
cp pristine.bin "$workname"
python3 - "$workname" <<'PY'
import sys
path = sys.argv[1]
data = bytearray(open(path, 'rb').read())
nodes = [i for i in range(len(data) - 4) if data[i:i + 4] == b'TREE']
for i in nodes[2:]:          # the chunk indexes follow the group's nodes
    data[i] ^= 0xff
open(path, 'wb').write(data)
PY
check_refused 'damaged chunk index'
echo "corrupt_block: resume refused a flipped byte in finished block $block ($msg1) and a damaged chunk index (one line, exit 2 or 1, no final file marked complete)"
exit 0
