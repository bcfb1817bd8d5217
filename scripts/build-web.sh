#!/usr/bin/env bash
# Builds the visualiser's web page into web/dist/: index.html, the JS glue
# (tirecontact-web.js) and the WebAssembly (tirecontact-web_bg.wasm), with
# gzip (and, if `brotli` is installed, brotli) copies of the last two
# (.gz, .br) for servers that send pre-compressed files. Serve the folder
# with any static server and open index.html, e.g.
#
#   scripts/build-web.sh && python3 -m http.server -d web/dist 8080
#
# The page is built with Debian's `rustc-web` compiler (which builds std for
# wasm32-unknown-unknown from its source, RUSTC_BOOTSTRAP=1 and
# -Zbuild-std inside this script only); the native build keeps using
# rustup's toolchain. Idempotent: it installs what is missing (apt packages
# as root, wasm-bindgen-cli of the version Cargo.lock pins with cargo) and
# reuses what is there.
#
# Environment: WEB_TOOLS (where wasm-bindgen-cli is installed, default
# ~/.cache/tirecontact-web), WEB_TARGET_DIR (cargo's target folder for the
# wasm build, default target/web), WEB_DIST (output, default web/dist).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
tools=${WEB_TOOLS:-$HOME/.cache/tirecontact-web}
target_dir=${WEB_TARGET_DIR:-$repo/target/web}
dist=${WEB_DIST:-$repo/web/dist}
say() { echo "build-web: $*"; }
started=$(date +%s)

# Debian's compiler for the web, its std source, its linker, and binaryen
# (wasm-opt).
pkgs=(rustc-web cargo-web rust-web-src libstd-rust-web-dev rust-web-llvm lld-22 binaryen)
need=()
for p in "${pkgs[@]}"; do
    dpkg -s "$p" >/dev/null 2>&1 || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
    if [ "$(id -u)" != 0 ]; then
        echo "build-web: needs ${need[*]}: run as root, or: sudo apt-get install -y ${need[*]}" >&2
        exit 2
    fi
    say "installing ${need[*]}"
    DEBIAN_FRONTEND=noninteractive apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}"
fi
web_rustc=/usr/bin/rustc
web_cargo=/usr/bin/cargo
"$web_rustc" --version

# wasm-bindgen-cli must be the version of the wasm-bindgen crate in Cargo.lock.
ver=$(awk '$0 == "name = \"wasm-bindgen\"" { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
[ -n "$ver" ] || { echo "build-web: no wasm-bindgen in Cargo.lock" >&2; exit 2; }
bindgen=$tools/bin/wasm-bindgen
if [ ! -x "$bindgen" ] || [ "$("$bindgen" --version)" != "wasm-bindgen $ver" ]; then
    say "installing wasm-bindgen-cli $ver into $tools (takes minutes, once)"
    # (--locked fails: its lock pins a crate version the index no longer has)
    CARGO_TARGET_DIR="$tools/build" cargo install -q wasm-bindgen-cli --version "$ver" --root "$tools"
    rm -rf "$tools/build"
fi

say "building the page (wasm32-unknown-unknown, release)"
t0=$(date +%s)
RUSTC="$web_rustc" RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR="$target_dir" \
    "$web_cargo" build --release --locked --bin tirecontact-web \
    --no-default-features --features web \
    --target wasm32-unknown-unknown -Zbuild-std=std,panic_abort
say "compiled in $(($(date +%s) - t0)) s"

raw=$target_dir/wasm32-unknown-unknown/release/tirecontact-web.wasm
# Debian's binaryen (108) is old: its wasm-opt is used only if it reads the
# compiler's output, and before wasm-bindgen (after it, it breaks the
# externref table wasm-bindgen adds: the page then fails to start).
input=$raw
if [ -f "$raw.opt" ] && [ "$raw.opt" -nt "$raw" ]; then
    say "wasm-opt: reusing its output for the unchanged build"
    input=$raw.opt
elif command -v wasm-opt >/dev/null 2>&1; then
    t0=$(date +%s)
    if wasm-opt -O2 --enable-reference-types --enable-bulk-memory --enable-mutable-globals \
        --enable-sign-ext --enable-nontrapping-float-to-int --enable-multivalue \
        "$raw" -o "$raw.opt" 2>"$raw.opt.log"; then
        say "wasm-opt -O2: $(stat -c %s "$raw") -> $(stat -c %s "$raw.opt") bytes in $(($(date +%s) - t0)) s"
        input=$raw.opt
    else
        say "wasm-opt $(wasm-opt --version 2>/dev/null | head -1) does not accept this output; skipped ($(head -c 200 "$raw.opt.log" | tr '\n' ' '))"
        rm -f "$raw.opt"
    fi
    rm -f "$raw.opt.log"
else
    say "no wasm-opt (binaryen): the page is not size-optimised"
fi

rm -rf "$dist"
mkdir -p "$dist"
"$bindgen" --target web --no-typescript --out-dir "$dist" --out-name tirecontact-web "$input"
wasm=$dist/tirecontact-web_bg.wasm
cp web/index.html "$dist/"
# pre-compressed copies beside the files, for servers that send them with
# `Content-Encoding` (nginx's gzip_static / brotli_static, Caddy's
# `file_server precompressed`); the originals stay for the others
for f in "$wasm" "$dist/tirecontact-web.js"; do
    gzip -9 -n -k -f "$f"
    if command -v brotli >/dev/null 2>&1; then
        brotli -q 11 -k -f "$f"
    fi
done
br=""
[ -f "$wasm.br" ] && br=", $(stat -c %s "$wasm.br") bytes brotli"
say "web/dist: wasm $(stat -c %s "$wasm") bytes, $(stat -c %s "$wasm.gz") bytes gzipped$br; in $(($(date +%s) - started)) s"
