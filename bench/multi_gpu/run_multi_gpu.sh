#!/usr/bin/env bash
# The thesis's Table 5.2 on this machine's GPUs: the lattice problems of DESIGN.md (n = 50 ... 400,
# m = 1.5 and 3.015) on 1, 2, 4 and 8 GPUs (those visible), host->host through the CLI in both
# multi-GPU modes: one process driving every GPU (--gpus G) and one MPI rank per GPU (halo
# exchange). Partitioning, halo build and assembly are inside the times (the thesis left them
# out); each part's device-resident build time is in the one-process JSON ("gpus"). For n <= 200
# every multi-GPU list is also written and compared byte for byte with the one-GPU list.
# Appends one JSON line per run to OUT_DIR/multi_gpu.jsonl; then plot_multi_gpu.py checks every
# count against the closed-form lattice total and draws the table and plots.
# Usage: bench/multi_gpu/run_multi_gpu.sh BUILD_DIR OUT_DIR
#        [SIZES="50 100 ... 400"] [SPACINGS="1.5 3.015"] [GPUS="1 2 4 8"] [REPS=2] [DEVICES=0,0 to reuse one GPU]
set -eu
bin="$1/bin/horizon"; out="$2"; mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
visible=$(nvidia-smi -L | wc -l)
counts=(); for g in ${GPUS:-1 2 4 8}; do [ "$g" -le "$visible" ] || [ -n "${DEVICES:-}" ] && counts+=("$g"); done
devices() {  # the GPUs of a run on g GPUs: the first g visible, or DEVICES' first g entries
  local list; if [ -n "${DEVICES:-}" ]; then list=$(echo "$DEVICES" | cut -d, -f1-"$1"); else list=$(seq -s, 0 $(($1 - 1))); fi
  if [ "$1" -eq 1 ]; then echo "--device $list"; else echo "--gpus $list"; fi
}
record() {  # mode n m g rep json
  [ -n "$6" ] || { echo "run failed: $1 n=$2 m=$3 gpus=$4" >&2; exit 1; }
  echo "{\"mode\":\"$1\",\"n\":$2,\"m\":$3,\"gpus\":$4,\"rep\":$5,\"result\":$6}" >> "$out/multi_gpu.jsonl"
}
for n in ${SIZES:-50 100 150 200 250 300 350 400}; do
  for m in ${SPACINGS:-1.5 3.015}; do
    h=$(python3 -c "print($m * 10 / $n)")
    for g in "${counts[@]}"; do
      for rep in $(seq "${REPS:-2}"); do
        record one-process "$n" "$m" "$g" "$rep" \
          "$("$bin" search "lattice:$n" --horizon "$h" --backend cuda $(devices "$g") --json --quiet)"
        [ "$g" -gt 1 ] && record mpi "$n" "$m" "$g" "$rep" \
          "$(mpirun --oversubscribe -np "$g" "$bin" search "lattice:$n" --horizon "$h" \
             --backend cuda --exchange halo --json --quiet)"
      done
      echo "n=$n m=$m gpus=$g done" >&2
    done
    if [ "$n" -le 200 ]; then  # the lists themselves: every mode and GPU count against one GPU
      "$bin" search "lattice:$n" --horizon "$h" --backend cuda --out "$out/one" --quiet
      for g in "${counts[@]}"; do
        [ "$g" -gt 1 ] || continue
        "$bin" search "lattice:$n" --horizon "$h" --backend cuda $(devices "$g") --out "$out/many" --quiet
        mpirun --oversubscribe -np "$g" "$bin" search "lattice:$n" --horizon "$h" \
          --backend cuda --exchange halo --out "$out/ranks" --quiet
        for f in offsets indices; do
          cmp "$out/one.$f.npy" "$out/many.$f.npy" && cmp "$out/one.$f.npy" "$out/ranks.$f.npy"
        done
        echo "n=$n m=$m gpus=$g: lists identical to one GPU" | tee -a "$out/identical.txt" >&2
      done
      rm -f "$out"/one.* "$out"/many.* "$out"/ranks.*
    fi
  done
done
