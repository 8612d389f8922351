#!/usr/bin/env bash
# mpirun -np 3 horizon search ... --exchange X writes byte-for-byte the files of a serial run.
# Usage: mpi_cli_test.sh HORIZON_BINARY MPIEXEC WORK_DIR
set -eu
horizon="$1"; mpiexec="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"; cd "$work"
"$horizon" generate clusters --count 20000 --clusters 7 --sigma 0.6 --out points.npy
"$horizon" search points.npy --horizon 0.25 --backend serial --out serial --quiet
for exchange in thesis halo overlap; do
  for decomposition in rcb brick; do
    "$mpiexec" --oversubscribe -np 3 "$horizon" search points.npy --horizon 0.25 --exchange "$exchange" \
      --decomposition "$decomposition" --out "$exchange" --json --quiet > "$exchange.json"
    grep -q '"ranks":3' "$exchange.json"
    cmp serial.offsets.npy "$exchange.offsets.npy"
    cmp serial.indices.npy "$exchange.indices.npy"
  done
done
# The parallel writer (every rank writes its rows at their offsets) against the serial files, byte
# for byte, at 1-4 and 7 ranks; full and half lists; and a 5-point input where most ranks own nothing.
"$horizon" search points.npy --horizon 0.25 --backend serial --half --out serial_half --quiet
printf '0 0 0\n1 0 0\n0 1 0\n5 5 5\n5 5 5.5\n' > tiny.xyz
tiny=tiny.xyz
"$horizon" search "$tiny" --horizon 1.2 --backend serial --out serial_tiny --quiet
for ranks in 1 2 3 4 7; do
  "$mpiexec" --oversubscribe -np "$ranks" "$horizon" search points.npy --horizon 0.25 --exchange halo \
    --writer parallel --out parallel --json --quiet > parallel.json
  grep -q '"writer":"parallel"' parallel.json
  cmp serial.offsets.npy parallel.offsets.npy
  cmp serial.indices.npy parallel.indices.npy
  "$mpiexec" --oversubscribe -np "$ranks" "$horizon" search points.npy --horizon 0.25 --exchange overlap --half \
    --writer parallel --out parallel_half --quiet
  cmp serial_half.offsets.npy parallel_half.offsets.npy
  cmp serial_half.indices.npy parallel_half.indices.npy
  "$mpiexec" --oversubscribe -np "$ranks" "$horizon" search "$tiny" --horizon 1.2 --exchange thesis \
    --writer parallel --out parallel_tiny --quiet
  cmp serial_tiny.offsets.npy parallel_tiny.offsets.npy
  cmp serial_tiny.indices.npy parallel_tiny.indices.npy
done
# auto: the gather, unless rank 0 could not hold the list (here: --max-memory below twice its 1.6 MB)
"$mpiexec" --oversubscribe -np 3 "$horizon" search points.npy --horizon 0.25 --out auto --json --quiet > auto.json
"$mpiexec" --oversubscribe -np 3 "$horizon" search points.npy --horizon 0.25 --max-memory 2M --out auto_small \
  --json --quiet > auto_small.json
grep -q '"writer":"gather"' auto.json && grep -q '"writer":"parallel"' auto_small.json
cmp serial.indices.npy auto_small.indices.npy && cmp serial.offsets.npy auto_small.offsets.npy
[ -z "$(ls | grep '\.tmp\.')" ]  # no temporary file left behind
# A parallel write that cannot happen fails on every rank with one message and leaves nothing.
set +e
"$mpiexec" --oversubscribe -np 3 "$horizon" search points.npy --horizon 0.25 --writer parallel \
  --out missing_dir/list --quiet 2> dir_error.txt
status=$?
"$mpiexec" --oversubscribe -np 2 "$horizon" search points.npy --horizon 0.25 --writer parallel --format csv \
  --out list --quiet 2> csv_error.txt
csv_status=$?
set -e
[ "$status" -eq 2 ] && grep -q "output directory 'missing_dir' does not exist" dir_error.txt
[ "$(grep -c 'horizon: error' dir_error.txt)" -eq 1 ]  # agreed by the ranks: said once, no abort
[ "$csv_status" -eq 2 ] && grep -q "writes .npy files only" csv_error.txt
[ ! -e missing_dir ] && [ ! -e list.csv ]
# A bad input fails on every rank with status 2 and one clear message.
set +e
"$mpiexec" --oversubscribe -np 2 "$horizon" search missing.npy --horizon 1 --exchange halo 2> error.txt
status=$?
set -e
[ "$status" -ne 0 ] && grep -q "missing.npy: cannot open" error.txt
# Bond filters, block pairs and ParaView output under mpirun: applied on rank 0 to the gathered
# list, the same files as one node; refused with the parallel writer.
printf '[{"type": "disk", "center": [5, 5, 5], "normal": [1, 0, 0], "radius": 3}]' > disk.json
awk 'BEGIN { for (i = 0; i < 20000; i++) print i % 2 }' > blocks.txt
filtering="--bond-filters disk.json --blocks blocks.txt --block-pairs 0-0,1-1"
"$horizon" search points.npy --horizon 0.25 --backend serial $filtering --out filtered --vtk filtered.vtu --quiet
"$mpiexec" --oversubscribe -np 3 "$horizon" search points.npy --horizon 0.25 --exchange halo $filtering \
  --out mpi_filtered --vtk mpi_filtered.vtu --json --quiet > mpi_filtered.json
grep -q '"bonds_cut"' mpi_filtered.json && grep -q '"block_pairs":2' mpi_filtered.json
cmp filtered.offsets.npy mpi_filtered.offsets.npy
cmp filtered.indices.npy mpi_filtered.indices.npy
cmp filtered.vtu mpi_filtered.vtu
set +e
"$mpiexec" --oversubscribe -np 2 "$horizon" search points.npy --horizon 0.25 --exchange halo --writer parallel \
  $filtering --out p 2> parallel_filter_error.txt
status=$?
"$mpiexec" --oversubscribe -np 2 "$horizon" search points.npy --horizon 0.25 --exchange halo --blocks blocks.txt \
  --block-pairs 0-7 2> pair_error.txt
pair_status=$?
set -e
[ "$status" -ne 0 ] && grep -q "need the whole list on rank 0" parallel_filter_error.txt
[ "$pair_status" -ne 0 ] && grep -q "no point is in block 7" pair_error.txt
# A periodic box under mpirun: every exchange gives the one-node files; a point outside the box
# fails with status 2 and names it.
awk 'BEGIN { srand(3); for (i = 0; i < 5000; i++) printf "%.17g %.17g %.17g\n", 10 * rand(), 10 * rand(), 4 * rand() }' > box.xyz
"$horizon" search box.xyz --horizon 0.6 --box 10,10,4 --backend serial --out serial_box --quiet
for exchange in thesis halo overlap; do
  "$mpiexec" --oversubscribe -np 3 "$horizon" search box.xyz --horizon 0.6 --box 10,10,4 --exchange "$exchange" \
    --out "box_$exchange" --quiet
  cmp serial_box.offsets.npy "box_$exchange.offsets.npy"
  cmp serial_box.indices.npy "box_$exchange.indices.npy"
done
"$horizon" search box.xyz --horizon 0.6 --box 10,0,0 --half --backend serial --out serial_slab --quiet
"$mpiexec" --oversubscribe -np 2 "$horizon" search box.xyz --horizon 0.6 --box 10,0,0 --half --exchange halo \
  --decomposition brick --out slab --quiet
cmp serial_slab.offsets.npy slab.offsets.npy && cmp serial_slab.indices.npy slab.indices.npy
set +e
"$mpiexec" --oversubscribe -np 2 "$horizon" search box.xyz --horizon 0.6 --box 10,10,3 --exchange halo 2> box_error.txt
status=$?
set -e
[ "$status" -eq 2 ] && grep -q "outside the periodic box \[0, 3" box_error.txt
# Per-point radii under mpirun: each rule gives the one-node files (and the ParaView radii); a bad
# radius fails with status 2 naming the point.
awk 'BEGIN { srand(5); for (i = 0; i < 20000; i++) printf "%.17g\n", 0.1 + 0.3 * rand() }' > radii.txt
"$horizon" search points.npy --radii radii.txt --radius-rule scatter --backend serial --out serial_scatter \
  --vtk serial_scatter.vtu --quiet
"$horizon" search points.npy --radii radii.txt --radius-rule max --half --backend serial --out serial_max --quiet
for exchange in thesis halo overlap; do
  "$mpiexec" --oversubscribe -np 3 "$horizon" search points.npy --radii radii.txt --radius-rule scatter \
    --exchange "$exchange" --out "scatter_$exchange" --vtk "scatter_$exchange.vtu" --json --quiet > radii.json
  grep -q '"radius_rule":"scatter"' radii.json
  cmp serial_scatter.offsets.npy "scatter_$exchange.offsets.npy"
  cmp serial_scatter.indices.npy "scatter_$exchange.indices.npy"
  cmp serial_scatter.vtu "scatter_$exchange.vtu"
  "$mpiexec" --oversubscribe -np 2 "$horizon" search points.npy --radii radii.txt --radius-rule max --half \
    --exchange "$exchange" --out "max_$exchange" --quiet
  cmp serial_max.offsets.npy "max_$exchange.offsets.npy" && cmp serial_max.indices.npy "max_$exchange.indices.npy"
done
sed '7s/.*/-1/' radii.txt > bad_radii.txt
set +e
"$mpiexec" --oversubscribe -np 2 "$horizon" search points.npy --radii bad_radii.txt --exchange halo 2> radius_error.txt
status=$?
set -e
[ "$status" -eq 2 ] && grep -q "point 6 has radius -1" radius_error.txt
# Queries under mpirun (one horizon; a radius per query): the one-node files, every exchange.
"$horizon" generate clusters --count 3000 --clusters 7 --sigma 0.8 --out queries.npy  # the same centres
awk 'BEGIN { srand(7); for (i = 0; i < 3000; i++) printf "%.17g\n", 0.05 + 0.3 * rand() }' > query_radii.txt
"$horizon" search points.npy --queries queries.npy --horizon 0.25 --backend serial --out serial_q --quiet
"$horizon" search points.npy --queries queries.npy --radii query_radii.txt --backend serial --out serial_qr \
  --vtk serial_qr.vtu --quiet
for exchange in thesis halo overlap; do
  "$mpiexec" --oversubscribe -np 3 "$horizon" search points.npy --queries queries.npy --horizon 0.25 \
    --exchange "$exchange" --out "q_$exchange" --quiet
  cmp serial_q.offsets.npy "q_$exchange.offsets.npy" && cmp serial_q.indices.npy "q_$exchange.indices.npy"
  "$mpiexec" --oversubscribe -np 2 "$horizon" search points.npy --queries queries.npy --radii query_radii.txt \
    --exchange "$exchange" --writer parallel --out "qr_$exchange" --quiet
  cmp serial_qr.offsets.npy "qr_$exchange.offsets.npy" && cmp serial_qr.indices.npy "qr_$exchange.indices.npy"
done
"$mpiexec" --oversubscribe -np 3 "$horizon" search points.npy --queries queries.npy --radii query_radii.txt \
  --out qr_vtk --vtk qr.vtu --quiet
cmp serial_qr.vtu qr.vtu
# An atomistic system under mpirun: a triclinic cell from an extended XYZ file (open along c),
# atoms in and around it, a cutoff larger than half the cell; ids, shifts, distances and vectors
# from both writers are the one-node files, every exchange. A smaller cell from --cell, half.
awk 'BEGIN { srand(11); print 3000; print "Lattice=\"8 0 0 2 7 0 1 1.5 6\" Properties=species:S:1:pos:R:3 pbc=\"T T F\"";
  for (i = 0; i < 3000; i++) { f = 1.4 * rand() - 0.2; g = 1.4 * rand() - 0.2; h = rand();
    printf "Si %.17g %.17g %.17g\n", 8 * f + 2 * g + h, 7 * g + 1.5 * h, 6 * h } }' > cell.extxyz
"$horizon" search cell.extxyz --horizon 4.5 --outputs d,D,S --backend serial --out serial_cell --quiet
for exchange in thesis halo overlap; do
  for writer in gather parallel; do
    "$mpiexec" --oversubscribe -np 3 "$horizon" search cell.extxyz --horizon 4.5 --outputs d,D,S \
      --exchange "$exchange" --writer "$writer" --out "cell_$exchange" --quiet
    for array in offsets indices shifts distances vectors; do cmp "serial_cell.$array.npy" "cell_$exchange.$array.npy"; done
  done
done
head -300 box.xyz > small.xyz
"$horizon" search small.xyz --horizon 0.9 --cell "1.5 0 0 0.4 1.2 0 0.2 0.3 1.1" --pbc 1,1,1 --half --outputs S \
  --self-interaction --backend serial --out serial_small --quiet
"$mpiexec" --oversubscribe -np 2 "$horizon" search small.xyz --horizon 0.9 --cell "1.5 0 0 0.4 1.2 0 0.2 0.3 1.1" \
  --pbc 1,1,1 --half --outputs S --self-interaction --exchange halo --out small --quiet
for array in offsets indices shifts; do cmp "serial_small.$array.npy" "small.$array.npy"; done
echo "mpirun CLI: all strategies and both writers identical to serial"
