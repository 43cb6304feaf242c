//! `viewer3d [FILE] [--frames N] [--screenshot F.png] [--bench] [--size WxH]`: the 3D world
//! viewer. FILE is a RON scene (or a builtin scene's name); without one it opens the
//! forest world.

use craterfield_demos::common::{RunArgs, launch};
use craterfield_demos::viewer3d::{SceneSource, Viewer3dApp};

fn main() {
    let args = match RunArgs::parse(std::env::args().skip(1)) {
        Ok(args) => args,
        Err(e) => {
            eprintln!("viewer3d: {e}");
            std::process::exit(2);
        }
    };
    let source = SceneSource::from_args(&args);
    let bench = args.bench;
    let result = launch(
        "craterfield viewer3d",
        &args,
        Box::new(move |cc, driver| {
            let app = Viewer3dApp::new(cc, source, driver, bench)?;
            Ok(Box::new(app) as Box<dyn eframe::App>)
        }),
    );
    if let Err(error) = result {
        eprintln!("viewer3d: {error}");
        std::process::exit(error.exit_code());
    }
}
