#!/usr/bin/env bash
# Runs a study in N shards with GNU parallel (here, or on the machines of
# --sshloginfile), merges the parts and checks the merged table against a
# one-process run of the same study, byte for byte.
#
#   scripts/study_parallel.sh STUDY N [TIRECONTACT]
#
# TIRECONTACT is the binary (default: tirecontact on the PATH). With
# PARALLEL_SSH_LOGINS set to an --sshloginfile, the shards run on those
# machines (each needs the binary and the study's files at the same paths).
set -euo pipefail
study=$1
n=$2
bin=${3:-tirecontact}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
ssh_args=()
if [ -n "${PARALLEL_SSH_LOGINS:-}" ]; then
    ssh_args=(--sshloginfile "$PARALLEL_SSH_LOGINS")
fi
seq 1 "$n" | parallel --will-cite "${ssh_args[@]}" -j "$n" \
    "$bin" study run "$study" --shard {}/"$n" --threads 1 -o "$out/part{}.csv"
"$bin" study merge "$out"/part*.csv -o "$out/merged.csv"
"$bin" study run "$study" -o "$out/one.csv"
cmp "$out/merged.csv" "$out/one.csv"
echo "study_parallel: $n shards by GNU parallel merged into the one-process table ($(($(wc -l <"$out/one.csv") - 1)) rows)"
