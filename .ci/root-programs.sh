# Sourced by the firmware checks (.ci/firmware, cycles, firmware-nofpu, firmware-m33,
# animation, pico-emu): the root workspace's programs they run on the host — the lab's
# test binary, the lab's release programs and the render CLI.
#
# Run alone, a check builds and runs them through cargo. In .ci/run's firmware lane,
# CI_ROOT_PROGRAMS names a file the host lane writes once it has built them (the lab
# test binary's path in it); the checks wait for that file and run the programs
# directly: a cargo command there would wait for whatever the host lane is building,
# as cargo locks the target directory while it builds.

# Waits for the host lane's programs, then reads the test binary's path.
root_programs_wait() {
    while [ ! -e "$CI_ROOT_PROGRAMS" ]; do
        sleep 2
    done
    LAB_TEST_BIN=$(sed -n 's/^lab_test=//p' "$CI_ROOT_PROGRAMS")
    [ -x "$LAB_TEST_BIN" ] || { echo "error: no lab test binary in $CI_ROOT_PROGRAMS" >&2; exit 1; }
}

# The lab's tests (`cargo test --test lab ARGS...`): ARGS are the test binary's, a
# filter and flags such as --nocapture. Run from lab/, as cargo runs a test binary.
lab_test() {
    if [ -n "${CI_ROOT_PROGRAMS:-}" ]; then
        root_programs_wait
        (cd lab && "$LAB_TEST_BIN" "$@")
    else
        cargo test --test lab -- "$@"
    fi
}

# Builds the lab's release programs NAME... (`--features tools`), unless the host lane
# has: the binaries are target/release/examples/NAME.
lab_examples_build() {
    if [ -n "${CI_ROOT_PROGRAMS:-}" ]; then
        root_programs_wait
    else
        local args=()
        for name in "$@"; do args+=(--example "$name"); done
        cargo build -q --release -p embedded-raytracer-lab --features tools "${args[@]}"
    fi
}

# Runs the lab's release program NAME with ARGS (`cargo run --example NAME -- ARGS`).
lab_example() {
    local name=$1
    shift
    lab_examples_build "$name"
    "target/release/examples/$name" "$@"
}

# Builds the render CLI (target/release/ertrace), unless the host lane has. Alone: not
# together with the lab's programs, whose features cargo would unify with its own.
cli_build() {
    if [ -n "${CI_ROOT_PROGRAMS:-}" ]; then
        root_programs_wait
    else
        cargo build -q --release -p embedded-raytracer-cli
    fi
}
