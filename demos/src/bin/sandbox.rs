//! `sandbox`: craterfield's destruction sandbox (see the crate's README for the controls).

use craterfield_demos::common::{RunArgs, launch};
use craterfield_demos::sandbox::SandboxApp;

fn main() {
    let args = match RunArgs::parse(std::env::args().skip(1)) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("sandbox: {e}");
            std::process::exit(2);
        }
    };
    let file = args.file.clone();
    let bench = args.bench;
    let result = launch(
        "craterfield sandbox",
        &args,
        Box::new(move |cc, driver| {
            SandboxApp::new(cc, file.as_deref(), driver, bench)
                .map(|app| Box::new(app) as Box<dyn eframe::App>)
        }),
    );
    if let Err(e) = result {
        eprintln!("sandbox: {e}");
        std::process::exit(e.exit_code());
    }
}
