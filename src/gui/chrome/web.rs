//! The page around the visualiser when it runs in a browser: its address
//! (where a scene link is read and written) and its title. On the desktop
//! these do nothing: the window's title is eframe's viewport title there.

#[cfg(target_arch = "wasm32")]
use eframe::web_sys;

/// Whether the visualiser runs in a browser (no files, no threads).
pub const IN_BROWSER: bool = cfg!(target_arch = "wasm32");

/// What the browser does not do, shown where the desktop would do it.
pub const BROWSER_LIMITS: &str = "In the browser, Open reads a preset through the browser's \
    picker, Save As, Export > Run as CSV, Export > Plots as PNG (1600 × 1200 px) and the sweep's \
    PNG download their file; a preset naming a file beside it (a measured tyre or road) and \
    animation frames (a folder of PNG files) need the desktop app. Background work (a ring's identification, a large patch's set-up, \
    sweeps, spectra, the CSV's re-run) runs in slices within the frames, one core, with its \
    progress and Cancel.";

/// The page's address without its fragment, in a browser.
pub fn page_address() -> Option<String> {
    #[cfg(target_arch = "wasm32")]
    {
        let href = web_sys::window()?.location().href().ok()?;
        Some(href.split('#').next().unwrap_or("").to_string())
    }
    #[cfg(not(target_arch = "wasm32"))]
    None
}

/// The page's fragment (`#…`), in a browser.
pub fn page_fragment() -> Option<String> {
    #[cfg(target_arch = "wasm32")]
    {
        web_sys::window()?.location().hash().ok()
    }
    #[cfg(not(target_arch = "wasm32"))]
    None
}

/// Puts `link`'s fragment into the page's address (the browser's address
/// bar then holds the link); nothing on the desktop. The page's
/// `data-shared-fragment` tells its `hashchange` handler (index.html) that
/// this fragment is the app's own: another one, pasted into the address
/// bar, reloads the page on its scene.
pub fn show_link(link: &str) {
    #[cfg(target_arch = "wasm32")]
    if let (Some(window), Some((_, fragment))) = (web_sys::window(), link.split_once('#')) {
        if let Some(body) = window.document().and_then(|d| d.body()) {
            let _ = body.set_attribute("data-shared-fragment", fragment);
        }
        let _ = window.location().set_hash(fragment);
    }
    #[cfg(not(target_arch = "wasm32"))]
    let _ = link;
}

/// Sets the page's title to the window's, `NAME (FILE) — tirecontact`
/// (eframe's web runner does not show the viewport title); nothing on the
/// desktop.
pub fn set_page_title(title: &str) {
    #[cfg(target_arch = "wasm32")]
    if let Some(doc) = web_sys::window().and_then(|w| w.document()) {
        doc.set_title(title);
    }
    #[cfg(not(target_arch = "wasm32"))]
    let _ = title;
}

/// Writes the run's time and steps on the page's `<body>` as
/// `data-time-s` and `data-steps` (read by the page's tests and by
/// scripts measuring the speed in the page); nothing on the desktop.
pub fn publish_run(time_s: f64, steps: u64) {
    #[cfg(target_arch = "wasm32")]
    if let Some(body) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.body())
    {
        let _ = body.set_attribute("data-time-s", &format!("{time_s:.6}"));
        let _ = body.set_attribute("data-steps", &steps.to_string());
    }
    #[cfg(not(target_arch = "wasm32"))]
    let _ = (time_s, steps);
}

#[cfg(target_arch = "wasm32")]
thread_local! {
    /// The file the browser's picker read, waiting for the next frame; and
    /// whether a picker is open.
    static PICKED: std::cell::RefCell<(Option<(String, Vec<u8>)>, bool)> =
        const { std::cell::RefCell::new((None, false)) };
}

/// Opens the browser's file picker for a RON preset; the file read is
/// taken by [`take_picked`]. Nothing on the desktop (its file prompt is
/// used there).
pub fn pick_preset() {
    #[cfg(target_arch = "wasm32")]
    {
        PICKED.with(|p| p.borrow_mut().1 = true);
        wasm_bindgen_futures::spawn_local(async {
            let file = rfd::AsyncFileDialog::new()
                .add_filter("RON scene", &["ron"])
                .pick_file()
                .await;
            let read = match file {
                Some(f) => Some((f.file_name(), f.read().await)),
                None => None,
            };
            PICKED.with(|p| *p.borrow_mut() = (read, false));
        });
    }
}

/// Whether the browser's picker is open (the frame then polls for it).
pub fn picking() -> bool {
    #[cfg(target_arch = "wasm32")]
    {
        PICKED.with(|p| p.borrow().1)
    }
    #[cfg(not(target_arch = "wasm32"))]
    false
}

/// The file the browser's picker read since the last call: its name and
/// bytes.
pub fn take_picked() -> Option<(String, Vec<u8>)> {
    #[cfg(target_arch = "wasm32")]
    {
        PICKED.with(|p| p.borrow_mut().0.take())
    }
    #[cfg(not(target_arch = "wasm32"))]
    None
}

/// Offers `bytes` as a download named `file_name` (the browser's own
/// save); nothing on the desktop.
pub fn download(file_name: &str, bytes: Vec<u8>) {
    #[cfg(target_arch = "wasm32")]
    {
        let name = file_name.to_string();
        wasm_bindgen_futures::spawn_local(async move {
            if let Some(f) = rfd::AsyncFileDialog::new()
                .set_file_name(&name)
                .save_file()
                .await
            {
                let _ = f.write(&bytes).await;
            }
        });
    }
    #[cfg(not(target_arch = "wasm32"))]
    let _ = (file_name, bytes);
}
