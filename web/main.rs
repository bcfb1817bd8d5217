//! `tirecontact-web`: the visualiser in a web page (built for
//! `wasm32-unknown-unknown` by `scripts/build-web.sh`). It starts the app in
//! the page's canvas `#tirecontact` and, if it cannot, says why in the page.

#[cfg(target_arch = "wasm32")]
fn main() {
    use eframe::wasm_bindgen::JsCast;
    use eframe::web_sys;

    let Some(document) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    let say = |text: &str| {
        if let Some(el) = document.get_element_by_id("loading") {
            el.set_text_content(Some(text));
        }
    };
    let Some(canvas) = document
        .get_element_by_id("tirecontact")
        .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
    else {
        say("The page has no canvas #tirecontact.");
        return;
    };
    wasm_bindgen_futures::spawn_local(async move {
        let started = tirecontact::gui::start_in_page(canvas).await;
        if let Some(doc) = web_sys::window().and_then(|w| w.document())
            && let Some(el) = doc.get_element_by_id("loading")
        {
            match started {
                Ok(()) => el.remove(),
                Err(e) => el.set_text_content(Some(&format!(
                    "The visualiser could not start (WebGL needed): {e:?}"
                ))),
            }
        }
    });
}

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    eprintln!(
        "tirecontact-web is the visualiser's web page: build it with scripts/build-web.sh \
         (the desktop visualiser is `tirecontact gui`)"
    );
    std::process::exit(2);
}
