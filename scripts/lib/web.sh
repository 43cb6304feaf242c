# The web leg's tools and builds, sourced by scripts/test and scripts/web.
#
# Debian's Rust (rustc-web, the aarch64 leg's compiler) with std's sources (rust-web-src)
# builds std for wasm32-unknown-unknown (-Zbuild-std; rustup's toolchain here has no wasm32
# std), linking with lld-22. wasm-bindgen-cli, pinned to the lock's wasm-bindgen, makes the
# module a page can load and runs the wasm-bindgen tests in Chromium through its WebDriver.
# Everything is installed once: the Debian packages when missing, wasm-bindgen-cli into the
# cache folder, and std is built once per toolchain into the wasm target folder there.

# Where tools and build outputs live, outside the clone (a fresh machine starts it empty).
CRATERFIELD_CACHE=${CRATERFIELD_CACHE:-${XDG_CACHE_HOME:-${HOME:-/tmp}/.cache}/craterfield}
WEB_TOOLS=$CRATERFIELD_CACHE/tools
WEB_TARGET_DIR=$CRATERFIELD_CACHE/target-wasm
WEB_TARGET=wasm32-unknown-unknown

# What the web leg builds, in one cargo invocation so that everything shares one feature
# resolution and each dependency is built once: the library with every renderer (its
# browser tests) and the sandbox page.
WEB_TESTS=(-p craterfield -p craterfield-web --test golden_hash --test sim_determinism --test web_render --test web_march3d)
WEB_BUILD=("${WEB_TESTS[@]}" --lib)

WEB_PKGS=(rustc-web cargo-web rust-web-src rust-web-llvm lld-22 chromium chromium-driver python3)

# Prints the packages of WEB_PKGS that are not installed.
web_pkgs_missing() {
    local p
    for p in "${WEB_PKGS[@]}"; do
        [[ "$(dpkg-query -W -f='${db:Status-Abbrev}' "$p" 2>/dev/null)" == ii* ]] || echo "$p"
    done
}

# The wasm-bindgen version in Cargo.lock: the CLI must be exactly this one.
wasm_bindgen_version() {
    sed -n '/^name = "wasm-bindgen"$/{n;s/^version = "\(.*\)"$/\1/p;}' Cargo.lock
}

# A heading: scripts/test's `log` (a timed stage) where the caller has one, else a line.
web_log() {
    if declare -F log >/dev/null; then log "$@"; else echo "$@"; fi
}

ensure_web_tools() {
    local missing want
    mapfile -t missing < <(web_pkgs_missing)
    if ((${#missing[@]})); then
        web_log "installing the web leg's packages: ${missing[*]}"
        apt-get update -q
        DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
    fi
    want=$(wasm_bindgen_version)
    if [[ "$("$WEB_TOOLS/bin/wasm-bindgen" --version 2>/dev/null)" != "wasm-bindgen $want" ]]; then
        web_log "installing wasm-bindgen-cli $want into $WEB_TOOLS"
        cargo install --quiet --force wasm-bindgen-cli --version "=$want" --root "$WEB_TOOLS"
    fi
}

# cargo for wasm32 with Debian's Rust: `web_cargo build|test [args]`. Tests run in headless
# Chromium (web/webdriver.json gives it WebGPU).
web_cargo() {
    local cmd=$1
    shift
    # No clippy comes with Debian's Rust: warnings of the wasm32-only code are errors instead.
    PATH="/usr/bin:$PATH" RUSTC=/usr/bin/rustc RUSTDOC=/usr/bin/rustdoc RUSTC_BOOTSTRAP=1 \
        RUSTFLAGS="-D warnings" \
        CARGO_TARGET_DIR="$WEB_TARGET_DIR" \
        CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER="$WEB_TOOLS/bin/wasm-bindgen-test-runner" \
        WASM_BINDGEN_TEST_WEBDRIVER_JSON="$PWD/web/webdriver.json" \
        CHROMEDRIVER=/usr/bin/chromedriver \
        WASM_BINDGEN_TEST_TIMEOUT="${WASM_BINDGEN_TEST_TIMEOUT:-900}" \
        /usr/bin/cargo "$cmd" -Zbuild-std=std,panic_abort --target "$WEB_TARGET" "$@"
}

# Builds the sandbox page into $1: the module (release, in the build of WEB_BUILD, which the
# browser tests share), wasm-bindgen's loader and index.html. Prints the module's size, raw
# and as gzip would serve it.
build_web_page() {
    local out=$1 wasm
    web_cargo build --release --locked "${WEB_BUILD[@]}"
    mkdir -p "$out"
    # The name section (function names for a panic's stack trace, 18% of the module) costs
    # every visitor a download and no speed; eframe's panic hook still logs message and place.
    "$WEB_TOOLS/bin/wasm-bindgen" --target web --no-typescript --remove-name-section \
        --out-dir "$out" \
        "$WEB_TARGET_DIR/$WEB_TARGET/release/craterfield_web.wasm"
    cp web/index.html "$out/"
    wasm="$out/craterfield_web_bg.wasm"
    printf 'sandbox page: %s: %d bytes (%d gzipped)\n' "$wasm" \
        "$(stat -c %s "$wasm")" "$(gzip -9 -c "$wasm" | wc -c)"
}
