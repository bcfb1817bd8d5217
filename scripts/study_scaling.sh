#!/usr/bin/env bash
# Throughput of a study of 1000 runs of the paper preset (0.2 s each): one
# process on 1 and 2 threads, and GNU parallel with 2 jobs of one thread;
# each table equal to the one-thread table; the per-row time split and the
# start of a process.
#   scripts/study_scaling.sh [TIRECONTACT]   (a release build; default
#   target/release/tirecontact)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$(realpath "${1:-$here/target/release/tirecontact}")
work=$(mktemp -d /tmp/tirecontact-scaling.XXXXXX)
cat >"$work/study.ron" <<STUDY
Study(
    preset: "$here/presets/paper.ron",
    factors: [
        Factor(path: "speed_mps", values: Range(from: 8.0, to: 30.0, steps: 100)),
        Factor(path: "road.amplitude_m", values: Range(from: 0.0005, to: 0.0015, steps: 10)),
    ],
    design: FullFactorial,
    duration_s: Some(0.2),
)
STUDY
cd "$work"
wall() { /usr/bin/env python3 -c 'import sys,time,subprocess; t=time.time(); subprocess.run(sys.argv[1:],check=True); print(f"{time.time()-t:.2f}")' "$@"; }
"$bin" study plan study.ron
echo "| how | wall (s) | runs/s |"
echo "|---|---|---|"
for t in 1 2; do
    s=$(wall "$bin" study run study.ron --threads "$t" -o "t$t.csv" 2>"t$t.log")
    echo "| one process, $t thread(s) | $s | $(python3 -c "print(round(1000/$s))") |"
done
s=$(wall bash -c "seq 1 2 | parallel --will-cite -j2 '$bin' study run study.ron --shard {}/2 --threads 1 -o p{}.csv 2>/dev/null && '$bin' study merge p1.csv p2.csv -o pm.csv >/dev/null 2>&1")
echo "| GNU parallel, 2 jobs of 1 thread, and the merge | $s | $(python3 -c "print(round(1000/$s))") |"
cmp t1.csv t2.csv && cmp t1.csv pm.csv && echo "(the three tables are byte for byte the same)"
echo
grep -h "per row" t1.log t2.log
start=$(python3 -c 'import sys,time,subprocess
t=time.time()
for _ in range(50): subprocess.run([sys.argv[1], "--version"], check=True, stdout=subprocess.DEVNULL)
print(f"{(time.time()-t)/50*1e3:.1f}")' "$bin")
echo "process start and exit: $start ms"
rm -rf "$work"
