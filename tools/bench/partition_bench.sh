#!/bin/bash
# partition_bench.sh VOLUME ISO EPS_VOXELS BLOCK [BIN_DIR] [INSIDE]
# Partitioned meshing (docs/partitioned.md) against one process, same run, on this machine:
#   one process, 1 thread, no blocks (the baseline); one process, 2 threads, no blocks;
#   the blocks on 2 threads (the thread engine); mpirun -np 2 with 1 thread per process;
#   mpirun -np 8 --oversubscribe with 1 thread per process, without and with --release-blocks.
# BLOCK: a number B for --blocks B (cubes), or count=N for --block-count N (N blocks of about
# equal work; the -np 8 rows are left out, since eight processes would share N blocks).
# Prints a markdown table: wall seconds, the largest peak memory of one process, the most samples
# one process read (a share of the file: mpirun reads MRC and raw files in part), vertices, and
# time and memory as ratios to the baseline. Every partitioned mesh must equal the thread engine's, byte
# for byte (the column "same mesh"; a --release-blocks run may differ from it, see docs/partitioned.md).
set -u
VOL=$1; ISO=$2; EPS=$3; B=$4; BIN=${5:-build/bin}; INSIDE=${6:-above}
OUT=$(mktemp -d); trap 'rm -rf "$OUT"' EXIT
case $B in
  count=*) PART="--block-count ${B#count=}"; WIDE=0 ;;
  *) PART="--blocks $B"; WIDE=1 ;;
esac
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
run() { # NAME LAUNCHER... -- ISODEL ARGS
  local name=$1; shift
  local t0 t1
  t0=$(date +%s.%N)
  "$@" mesh "$VOL" --iso "$ISO" --inside "$INSIDE" --eps-voxels "$EPS" -o "$OUT/$name.ply" --stats "$OUT/$name.json" \
    --quiet ${EXTRA:-} || { echo "| $name | failed | | | | | |"; return; }
  t1=$(date +%s.%N)
  echo "$name $(echo "$t1 - $t0" | bc)" >> "$OUT/times"
}
EXTRA="--threads 1" run one_1t "$BIN/isodel"
EXTRA="--threads 2" run one_2t "$BIN/isodel"
EXTRA="--threads 2 $PART" run blocks_2t "$BIN/isodel"
EXTRA="--threads 1 $PART" run mpi_np2 mpirun -np 2 --bind-to none "$BIN/isodel"
if [ $WIDE = 1 ]; then
  EXTRA="--threads 1 $PART" run mpi_np8 mpirun -np 8 --bind-to none "$BIN/isodel"
  EXTRA="--threads 1 $PART --release-blocks" run mpi_np8_rel mpirun -np 8 --bind-to none "$BIN/isodel"
fi
PART="$PART" /usr/bin/python3 - "$OUT" <<'PY'
import json, os, sys
out = sys.argv[1]
times = dict(l.split() for l in open(os.path.join(out, "times")))
def row(name):
    s = json.load(open(os.path.join(out, name + ".json")))
    p = s.get("partition", {})
    mem = p.get("max_process_peak_memory_bytes") or s.get("peak_memory_bytes", 0)
    return float(times[name]), mem, s["counts"]["vertices"], p
base_t, base_m, base_v, _ = row("one_1t")
ref = open(os.path.join(out, "blocks_2t.ply"), "rb").read() if os.path.exists(os.path.join(out, "blocks_2t.ply")) else None
print("| run | wall s | vs 1 process 1 thread | peak memory per process | vs baseline | samples read per process | vertices | blocks, rounds | same mesh |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |")
for name, label in [("one_1t", "1 process, 1 thread"), ("one_2t", "1 process, 2 threads"),
                    ("blocks_2t", "blocks (" + os.environ.get("PART", "") + "), 2 threads"), ("mpi_np2", "mpirun -np 2, 1 thread each"),
                    ("mpi_np8", "mpirun -np 8, 1 thread each"),
                    ("mpi_np8_rel", "mpirun -np 8, 1 thread each, --release-blocks")]:
    if name not in times: continue
    t, m, v, p = row(name)
    same = ""
    if p and name.endswith("_rel"):
        same = "(released: its own mesh)"  # tests/cli/test_partitioned_mpi_cli.cpp compares it with the threads'
    elif p:
        same = "yes" if open(os.path.join(out, name + ".ply"), "rb").read() == ref else "NO"
    blocks = f"{p.get('blocks')}, {p.get('exchange_rounds')}" if p else ""
    # mpirun on a file read in part (MRC, raw): the most one process read, as a share of the file.
    read = f"{p['max_process_samples_read'] / p['file_samples']:.2f}" if p.get("file_samples") else "1 (whole file)"
    print(f"| {label} | {t:.2f} | {base_t / t:.2f}x | {m / 2**20:.0f} MiB | {m / base_m:.2f} | {read} | {v} | {blocks} | {same} |")
PY
