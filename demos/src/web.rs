//! The sandbox in a browser (WebAssembly): files opened through the page's file picker and
//! recordings saved as downloads, where the native build reads and writes paths. The page
//! itself, which starts eframe's web runner on a canvas, is the `craterfield-web` package.

use std::cell::RefCell;
use std::rc::Rc;

use wasm_bindgen::JsCast;

/// The largest file the page reads: a level's limit, which is larger than a replay's.
const MAX_FILE_BYTES: f64 = craterfield::field2d::MAX_LEVEL_BYTES as f64;

/// A file handed over by the page, or why it could not be read.
pub type PickedFile = Result<(String, Vec<u8>), String>;

/// Files the page has read, waiting for the app's next frame.
#[derive(Clone, Default)]
pub struct FileInbox(Rc<RefCell<Vec<PickedFile>>>);

impl FileInbox {
    /// Everything that arrived since the last call.
    pub fn take(&self) -> Vec<PickedFile> {
        std::mem::take(&mut *self.0.borrow_mut())
    }

    fn push(&self, file: PickedFile) {
        self.0.borrow_mut().push(file);
    }
}

/// Opens the browser's file picker for levels and replays; what the user chooses is read
/// asynchronously into `inbox`, and `ctx` is asked to repaint when it is there.
pub fn pick_files(inbox: &FileInbox, ctx: &egui::Context) -> Result<(), String> {
    let input: web_sys::HtmlInputElement = document()?
        .create_element("input")
        .map_err(js_error)?
        .dyn_into()
        .map_err(|_| "the page made no input element".to_string())?;
    input.set_type("file");
    input.set_accept(".ron,.replay");
    input.set_multiple(true);
    let (chosen, inbox, ctx) = (input.clone(), inbox.clone(), ctx.clone());
    let on_change = wasm_bindgen::closure::Closure::once_into_js(move || {
        let Some(files) = chosen.files() else {
            return;
        };
        for file in (0..files.length()).filter_map(|i| files.get(i)) {
            read_file(file, inbox.clone(), ctx.clone());
        }
    });
    input.set_onchange(Some(on_change.unchecked_ref()));
    input.click();
    Ok(())
}

/// Reads `file` (refusing one past [`MAX_FILE_BYTES`] before reading it) into `inbox`.
fn read_file(file: web_sys::File, inbox: FileInbox, ctx: egui::Context) {
    let name = file.name();
    if file.size() > MAX_FILE_BYTES {
        inbox.push(Err(format!(
            "{name}: {} bytes, more than the {MAX_FILE_BYTES} a level or replay may have",
            file.size()
        )));
        ctx.request_repaint();
        return;
    }
    wasm_bindgen_futures::spawn_local(async move {
        let read = wasm_bindgen_futures::JsFuture::from(file.array_buffer()).await;
        inbox.push(match read {
            Ok(buffer) => Ok((name, js_sys::Uint8Array::new(&buffer).to_vec())),
            Err(e) => Err(format!("{name}: {}", js_error(e))),
        });
        ctx.request_repaint();
    });
}

/// Reads a file dropped onto the page into `inbox` (egui hands over a handle; the bytes
/// come asynchronously).
pub fn read_dropped(file: egui::DroppedFileHandle, inbox: &FileInbox, ctx: &egui::Context) {
    let (inbox, ctx) = (inbox.clone(), ctx.clone());
    wasm_bindgen_futures::spawn_local(async move {
        let name = file.path().display().to_string();
        inbox.push(match file.bytes_async().await {
            Ok(bytes) if bytes.len() as f64 > MAX_FILE_BYTES => Err(format!(
                "{name}: {} bytes, more than the {MAX_FILE_BYTES} a level or replay may have",
                bytes.len()
            )),
            Ok(bytes) => Ok((name, bytes)),
            Err(e) => Err(format!("{name}: {e}")),
        });
        ctx.request_repaint();
    });
}

/// Offers `bytes` to the user as a download named `name`.
pub fn download(name: &str, bytes: &[u8]) -> Result<(), String> {
    let parts = js_sys::Array::of1(&js_sys::Uint8Array::from(bytes));
    let blob = web_sys::Blob::new_with_u8_array_sequence(&parts).map_err(js_error)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(js_error)?;
    let anchor: web_sys::HtmlAnchorElement = document()?
        .create_element("a")
        .map_err(js_error)?
        .dyn_into()
        .map_err(|_| "the page made no anchor element".to_string())?;
    anchor.set_href(&url);
    anchor.set_download(name);
    anchor.click();
    web_sys::Url::revoke_object_url(&url).map_err(js_error)
}

fn document() -> Result<web_sys::Document, String> {
    web_sys::window()
        .and_then(|w| w.document())
        .ok_or_else(|| "no page document".to_string())
}

fn js_error(e: wasm_bindgen::JsValue) -> String {
    e.as_string().unwrap_or_else(|| format!("{e:?}"))
}
