//! The one harness of the GPU test binaries (`harness = false`): every test runs on the
//! adapter wgpu finds (Mesa's lavapipe in CI), one at a time on one shared context. Without
//! an adapter each test reports itself ignored, never passed; with `CI` set a missing adapter
//! fails every test instead. A test fails by returning an error or by panicking.

use std::sync::{Mutex, OnceLock};

use craterfield::gpu::GpuContext;
use libtest_mimic::{Arguments, Failed, Trial};

/// What a GPU test returns.
pub(crate) type TestResult = Result<(), Failed>;
/// A GPU test: its body, given the shared context.
pub(crate) type GpuTest = fn(&GpuContext) -> TestResult;

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
    let args = Arguments::from_args();
    let ci = std::env::var_os("CI").is_some();
    let missing = context().is_none();
    let trials = tests
        .iter()
        .map(|&(name, test)| {
            Trial::test(name, move || match context() {
                // A test that panicked while holding the context poisons the lock; the next
                // test takes the context anyway (the device is all they share, though a
                // panic inside an error scope leaves that scope pushed on it).
                Some(ctx) => test(&ctx.lock().unwrap_or_else(|e| e.into_inner())),
                None if ci => Err("no GPU adapter, and CI is set: GPU tests must run in CI".into()),
                None => Err("no GPU adapter".into()),
            })
            .with_ignored_flag(missing && !ci)
        })
        .collect();
    libtest_mimic::run(&args, trials).exit()
}
