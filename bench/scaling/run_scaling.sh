#!/usr/bin/env bash
# The thesis's chapter-4 study: lattice problems on p = 1..16 ranks for every exchange strategy,
# one core per rank (serial backend). Appends one JSON line per run to OUT (horizon's --json
# plus study, n, m, rep). STUDIES="strong weak" and REPS=3 by default. Usage: bench/scaling/run_scaling.sh BUILD_DIR OUT.jsonl [MAX_RANKS] [M...]
set -u
bin="$1/bin/horizon"; out="$2"; max_ranks="${3:-16}"; shift 3 2>/dev/null || shift $#
spacings=("${@:-1.5 3.015}"); [ $# -eq 0 ] && spacings=(1.5 3.015)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
run() {  # study n m p exchange rep
  local h; h=$(python3 -c "print($3 * 10 / $2)")
  mpirun --oversubscribe --bind-to core -np "$4" "$bin" search "lattice:$2" --horizon "$h" \
    --backend serial --exchange "$5" --json --quiet 2>/dev/null \
    | sed "s/^{/{\"study\":\"$1\",\"n\":$2,\"m\":$3,\"rep\":$6,/" >> "$out"
}
studies="${STUDIES:-strong weak}"; reps="${REPS:-3}"
ranks=(); for p in 1 2 4 8 16 32; do [ "$p" -le "$max_ranks" ] && ranks+=("$p"); done
for m in "${spacings[@]}"; do
  [[ " $studies " == *" strong "* ]] && for n in 37 47 53 59 63 80; do
    for p in "${ranks[@]}"; do
      for x in thesis halo overlap; do
        for rep in $(seq "$reps"); do run strong "$n" "$m" "$p" "$x" "$rep"; done
      done
    done
  done
  # Weak scaling: about 10^6 points per rank.
  [[ " $studies " == *" weak "* ]] && for p in "${ranks[@]}"; do
    n=$(python3 -c "print(round(100 * $p ** (1/3)))")
    for x in thesis halo overlap; do run weak "$n" "$m" "$p" "$x" 1; done
  done
done
