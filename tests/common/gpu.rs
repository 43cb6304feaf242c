//! The one harness of the GPU test binaries (`harness = false`): every test runs on the
//! adapter wgpu finds (Mesa's lavapipe in CI), one at a time on one shared context. Without
//! an adapter each test reports itself ignored, never passed; with `CI` set a missing adapter
//! fails every test instead. A test fails by returning an error or by panicking.
//!
//! No test can hang silently. The tests run on one thread, so libtest prints
//! `test NAME ...` before each one starts. A watchdog aborts the binary when a test runs past
//! its deadline ([`GPU_TEST_TIMEOUT_VAR`], default [`DEFAULT_TEST_TIMEOUT`]), naming the test
//! and its last [`phase`]. The tests' own waits for the GPU last at most [`GPU_WAIT`]. A
//! driver stuck in a synchronous call, such as compiling a shader, is caught only by the
//! watchdog.

use std::sync::mpsc::{RecvTimeoutError, channel};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use craterfield::gpu::GpuContext;
use libtest_mimic::{Arguments, Failed, Trial};

/// What a GPU test returns.
pub(crate) type TestResult = Result<(), Failed>;
/// A GPU test: its body, given the shared context.
pub(crate) type GpuTest = fn(&GpuContext) -> TestResult;
/// A test of a GPU binary that needs no adapter (it runs, and passes or fails, everywhere).
pub(crate) type PlainTest = fn() -> TestResult;

/// The environment variable that sets each test's deadline in whole seconds (`0` turns the
/// watchdog off, for a debugger).
pub(crate) const GPU_TEST_TIMEOUT_VAR: &str = "CRATERFIELD_GPU_TEST_TIMEOUT_S";

/// Each test's deadline when [`GPU_TEST_TIMEOUT_VAR`] is unset. On lavapipe with two cores
/// the slowest test (`march3d_gpu`'s comparison with the CPU tracer) takes under 30 s. The
/// deadline is far above that, and below the 300 s that `scripts/gpu-check` gives each test
/// binary, so the watchdog names the stuck test before the script kills the binary.
pub(crate) const DEFAULT_TEST_TIMEOUT: Duration = Duration::from_secs(240);

/// The longest the tests wait for submitted GPU work (`craterfield::gpu::wait_for`). It is
/// shorter than a test's deadline, so a GPU that never finishes fails that test with an
/// error and the rest still run.
pub(crate) const GPU_WAIT: Duration = Duration::from_secs(120);

/// What the running test is doing now; the watchdog prints it.
static PHASE: Mutex<String> = Mutex::new(String::new());

/// Records what the running test does next (e.g. `forest-all: GPU compile and march`), so
/// a watchdog abort says where the test stopped, not only which test it was.
pub(crate) fn phase(what: impl Into<String>) {
    *PHASE.lock().unwrap_or_else(|e| e.into_inner()) = what.into();
}

/// The deadline from [`GPU_TEST_TIMEOUT_VAR`]; `None` when it is `0`. An unreadable value
/// stops the binary, so a typo cannot silently fall back to the default.
fn test_timeout() -> Option<Duration> {
    let Some(value) = std::env::var_os(GPU_TEST_TIMEOUT_VAR) else {
        return Some(DEFAULT_TEST_TIMEOUT);
    };
    let seconds: u64 = value
        .to_str()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| {
            panic!("{GPU_TEST_TIMEOUT_VAR} must be whole seconds (0: no watchdog), got {value:?}")
        });
    (seconds > 0).then(|| Duration::from_secs(seconds))
}

/// Runs `body` as `name`. If it is still running after `limit`, the watchdog prints the
/// name and the last phase, then aborts the process. It aborts rather than exits: `exit`
/// runs atexit handlers, which may block on locks held by a driver stuck in a compile.
fn watched<R>(name: &str, limit: Option<Duration>, body: impl FnOnce() -> R) -> R {
    let Some(limit) = limit else {
        return body();
    };
    phase("start");
    let (done, finished) = channel::<()>();
    let started = Instant::now();
    let name = name.to_owned();
    let watchdog = std::thread::spawn(move || {
        // Disconnected (the body returned or unwound) ends the watch.
        if let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(limit) {
            let phase = PHASE.lock().map(|p| p.clone()).unwrap_or_default();
            eprintln!(
                "\nGPU test `{name}` still running after {:.0?} (deadline {limit:?}, set \
                 {GPU_TEST_TIMEOUT_VAR} to change it); last phase: {phase}; aborting",
                started.elapsed()
            );
            std::process::abort();
        }
    });
    let out = body();
    drop(done);
    // The watchdog sees the disconnect at once; joining keeps no thread behind.
    let _ = watchdog.join();
    out
}

/// The context all tests of the binary share, made on first use (`None`: no adapter).
fn context() -> Option<&'static Mutex<GpuContext>> {
    static CONTEXT: OnceLock<Option<Mutex<GpuContext>>> = OnceLock::new();
    CONTEXT
        .get_or_init(|| match GpuContext::new() {
            Ok(ctx) => {
                eprintln!("GPU adapter: {}", ctx.describe());
                Some(Mutex::new(ctx))
            }
            Err(e) => {
                eprintln!("no GPU adapter: {e}");
                None
            }
        })
        .as_ref()
}

/// Runs `tests` with libtest's command line (filters, `--list`, `--ignored`) and exits.
pub(crate) fn run(tests: &[(&'static str, GpuTest)]) -> ! {
    run_with(tests, &[])
}

/// [`run`] plus `plain` tests that need no adapter: they run, under the same watchdog, on a
/// machine without a GPU too.
pub(crate) fn run_with(
    tests: &[(&'static str, GpuTest)],
    plain: &[(&'static str, PlainTest)],
) -> ! {
    let mut args = Arguments::from_args();
    // The GPU tests take turns on one context anyway. On one thread libtest-mimic prints
    // `test NAME ...` before each test starts; with several it prints a line only when a
    // test ends, so a stuck test would leave no name.
    args.test_threads = Some(1);
    let timeout = test_timeout();
    let ci = std::env::var_os("CI").is_some();
    let missing = watched("(GPU adapter setup)", timeout, || context().is_none());
    let gpu = tests.iter().map(|&(name, test)| {
        Trial::test(name, move || {
            watched(name, timeout, || match context() {
                // A test that panicked while holding the context poisons the lock; the next
                // test takes the context anyway (the device is all they share, though a
                // panic inside an error scope leaves that scope pushed on it).
                Some(ctx) => test(&ctx.lock().unwrap_or_else(|e| e.into_inner())),
                None if ci => Err("no GPU adapter, and CI is set: GPU tests must run in CI".into()),
                None => Err("no GPU adapter".into()),
            })
        })
        .with_ignored_flag(missing && !ci)
    });
    let plain = plain
        .iter()
        .map(|&(name, test)| Trial::test(name, move || watched(name, timeout, test)));
    libtest_mimic::run(&args, gpu.chain(plain).collect()).exit()
}
