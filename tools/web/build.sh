#!/usr/bin/env bash
# Builds the page into one folder of static files (default `target/web/`): the kernel
# compiled to WebAssembly, wasm-bindgen's ES-module glue (`--target web`: no bundler)
# and the page itself (`tools/web/www/`). Serve the folder as it is (`docs/web.md`).
#
#   bash tools/web/build.sh [OUT_DIR]
#
# Installs what it lacks: the `wasm32-unknown-unknown` standard library (rustup) and
# the wasm-bindgen CLI of exactly the version `tools/web/Cargo.toml` pins (its output
# must match the crate's). Fails if the gzip'd `.wasm` is over MAX_WASM_GZ bytes.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-$root/target/web}
# The size budget of the page's WebAssembly, gzip'd (what a server sends).
MAX_WASM_GZ=400000

cd "$root"
version=$(sed -n 's/^wasm-bindgen = "=\([0-9.]*\)".*/\1/p' tools/web/Cargo.toml)
[[ -n $version ]] || { echo "tools/web/Cargo.toml: no exact wasm-bindgen version" >&2; exit 1; }

if command -v rustup >/dev/null && ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    rustup target add wasm32-unknown-unknown
fi
if [[ $(wasm-bindgen --version 2>/dev/null) != "wasm-bindgen $version" ]]; then
    echo "installing wasm-bindgen-cli $version (several minutes, once)"
    cargo install wasm-bindgen-cli --version "=$version" --locked
fi

# The page's build only (the workspace's release profile stays as the host tools have
# it): link-time optimisation, one codegen unit and optimising for size keep the module
# within its budget (`z` makes it larger than `s` here; `3` is over the budget).
CARGO_PROFILE_RELEASE_LTO=true \
CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1 \
CARGO_PROFILE_RELEASE_OPT_LEVEL=s \
    cargo build --release --locked -p embedded-raytracer-web --target wasm32-unknown-unknown

rm -rf "$out"
mkdir -p "$out"
wasm-bindgen --target web --no-typescript --remove-name-section --remove-producers-section \
    --out-dir "$out/pkg" \
    "${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/release/embedded_raytracer_web.wasm"
cp tools/web/www/* "$out/"

wasm="$out/pkg/embedded_raytracer_web_bg.wasm"
gz=$(gzip -9 -c "$wasm" | wc -c)
echo "$out: $(wc -c <"$wasm") bytes of WebAssembly, $gz gzip'd (budget $MAX_WASM_GZ)"
if ((gz > MAX_WASM_GZ)); then
    echo "error: the gzip'd .wasm is over its budget of $MAX_WASM_GZ bytes" >&2
    exit 1
fi
