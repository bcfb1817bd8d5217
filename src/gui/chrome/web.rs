//! The page around the visualiser when it runs in a browser: its address
//! (where a scene link is read and written) and its title. On the desktop
//! these do nothing: the window's title is eframe's viewport title there.

/// Whether the visualiser runs in a browser (no files, no threads).
pub const IN_BROWSER: bool = cfg!(target_arch = "wasm32");

/// What the browser does not do, shown where the desktop would do it.
pub const BROWSER_LIMITS: &str = "In the browser, files are opened and saved through the \
    browser's own picker and downloads, and background work (identification, sweeps, spectra, \
    exports) runs in the page between frames, which pauses the page until it ends.";

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
/// bar then holds the link); nothing on the desktop.
pub fn show_link(link: &str) {
    #[cfg(target_arch = "wasm32")]
    if let (Some(window), Some((_, fragment))) = (web_sys::window(), link.split_once('#')) {
        let _ = window.location().set_hash(fragment);
    }
    #[cfg(not(target_arch = "wasm32"))]
    let _ = link;
}

/// Sets the page's title to `NAME — tirecontact` (eframe's web runner
/// does not show the viewport title); nothing on the desktop.
pub fn set_page_title(scene_name: &str) {
    #[cfg(target_arch = "wasm32")]
    if let Some(doc) = web_sys::window().and_then(|w| w.document()) {
        doc.set_title(&format!("{scene_name} — tirecontact"));
    }
    #[cfg(not(target_arch = "wasm32"))]
    let _ = scene_name;
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
