//! Menu bar (File, Presets, Export, View) and the transport controls:
//! play/pause, step, N steps, reset, speed, current time and real-time factor.

use crate::gui::model::command::{Command, View};
use crate::gui::model::presets::SHIPPED;
use crate::gui::model::time_control::Speed;
use crate::gui::widgets::NARROW_PX;
use egui::{Id, RichText, Ui};

/// What the toolbar shows (read-only snapshot of the app).
pub struct ToolbarStatus {
    pub playing: bool,
    pub speed: Speed,
    pub time_s: f64,
    pub duration_s: f64,
    pub steps: u64,
    pub achieved_factor: f64,
    pub view: View,
    pub exporting_csv: bool,
    pub classroom: bool,
    pub mode_bars: bool,
    pub exporting_frames: bool,
    /// The scene's points lie in several rows across the tread (a patch):
    /// its heat map can be exported.
    pub patch: bool,
    /// The editing panel is shown in place of the views (a phone): a view
    /// chosen, even the current one, brings the views back.
    pub editing: bool,
    /// What Undo and Redo would take back or make again (in words, with
    /// units); `None` when there is nothing.
    pub undo: Option<String>,
    pub redo: Option<String>,
}

/// The menu bar. Long but flat: the File, Presets, View and Help menus one
/// after another, each item as it appears. Where the view items do not fit
/// on the line (the width the flat bar took when last drawn is more than
/// the window's) they fold into a View menu; in a window narrower than
/// [`NARROW_PX`] (a phone) the bar folds into three menus, Menu (File,
/// Presets, Guided tour, Export), View and Help, so that it fits the width.
pub fn menu_bar(ui: &mut Ui, st: &ToolbarStatus, cmds: &mut Vec<Command>) {
    let width = ui.available_width();
    let narrow = width < NARROW_PX;
    let flat_id = Id::unique("tirecontact.menu_bar.flat_px");
    let flat_px = ui.data(|d| d.get_temp::<f32>(flat_id)).unwrap_or(0.0);
    let compact = !narrow && flat_px > width;
    egui::MenuBar::new().ui(ui, |ui| {
        let left = ui.min_rect().left();
        if compact {
            ui.menu_button("File", |ui| file_items(ui, st, cmds));
            ui.menu_button("Presets", |ui| preset_items(ui, cmds));
            ui.menu_button("Guided tour", |ui| guided_items(ui, cmds));
            ui.menu_button("Export", |ui| export_items(ui, st, cmds));
            // (classroom mode's own toggle stays on the bar: one click out)
            classroom_toggle(ui, st, cmds);
            ui.menu_button("View", |ui| view_tabs(ui, st, cmds));
            super::help_menu::show(ui, cmds);
            return;
        }
        if narrow {
            ui.menu_button("Menu", |ui| {
                ui.menu_button("File", |ui| file_items(ui, st, cmds));
                ui.menu_button("Presets", |ui| preset_items(ui, cmds));
                ui.menu_button("Guided tour", |ui| guided_items(ui, cmds));
                ui.menu_button("Export", |ui| export_items(ui, st, cmds));
            });
            ui.menu_button("View", |ui| view_items(ui, st, cmds));
        } else {
            ui.menu_button("File", |ui| file_items(ui, st, cmds));
            ui.menu_button("Presets", |ui| preset_items(ui, cmds));
            ui.menu_button("Guided tour", |ui| guided_items(ui, cmds));
            ui.menu_button("Export", |ui| export_items(ui, st, cmds));
            ui.separator();
            view_items(ui, st, cmds);
            ui.separator();
        }
        super::help_menu::show(ui, cmds);
        if !narrow {
            // (the flat bar's width, whether or not it fitted: it folds from
            // the next frame while the window is narrower)
            let used = ui.min_rect().right() - left;
            ui.data_mut(|d| d.insert_temp(flat_id, used));
        }
    });
}

/// The File menu's items.
fn file_items(ui: &mut Ui, st: &ToolbarStatus, cmds: &mut Vec<Command>) {
    undo_items(ui, st, cmds);
    ui.separator();
    if ui
        .button("New")
        .on_hover_text("the default scene")
        .clicked()
    {
        cmds.push(Command::New);
    }
    if ui
        .add(egui::Button::new("Open…").shortcut_text("Ctrl+O"))
        .clicked()
    {
        cmds.push(Command::OpenDialog);
    }
    ui.menu_button("Open shipped preset", |ui| preset_items(ui, cmds));
    ui.separator();
    if ui
        .add(egui::Button::new("Save").shortcut_text("Ctrl+S"))
        .clicked()
    {
        cmds.push(Command::Save);
    }
    if ui
        .add(egui::Button::new("Save As…").shortcut_text("Ctrl+Shift+S"))
        .clicked()
    {
        cmds.push(Command::SaveAsDialog);
    }
    ui.separator();
    if ui
        .button("Share link")
        .on_hover_text(
            "copies a link that opens this scene in the visualiser's web page \
             (a measured tyre or road cannot travel in a link)",
        )
        .clicked()
    {
        cmds.push(Command::Share);
    }
    // a page is closed as a browser's tab is
    if !crate::gui::chrome::web::IN_BROWSER {
        ui.separator();
        if ui.button("Quit").clicked() {
            cmds.push(Command::Quit);
        }
    }
}

/// Undo and Redo, each saying what it would change (shortened; in full on
/// hover), disabled when there is nothing to undo or redo.
fn undo_items(ui: &mut Ui, st: &ToolbarStatus, cmds: &mut Vec<Command>) {
    let actions = super::edits_box::undo_actions([st.undo.as_deref(), st.redo.as_deref()]);
    for (label, what, key, cmd) in actions {
        let text = match what {
            Some(w) if !w.is_empty() => format!("{label} {}", shortened(w, 40)),
            _ => label.to_string(),
        };
        let button = egui::Button::new(text).shortcut_text(key);
        let r = ui.add_enabled(what.is_some(), button);
        let r = match what {
            Some(w) if !w.is_empty() => r.on_hover_text(w),
            Some(_) => r,
            None => r.on_disabled_hover_text(format!(
                "nothing to {} now (no scene edit, or one being prepared)",
                label.to_lowercase()
            )),
        };
        if r.clicked() {
            cmds.push(cmd);
        }
    }
}

/// `text` cut to `max` characters with an ellipsis.
fn shortened(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        return text.to_string();
    }
    let mut s: String = text.chars().take(max - 1).collect();
    s.push('…');
    s
}

/// The shipped presets; on the desktop also those reading a file beside
/// them, from a `presets/` folder (the repository's, or one beside the
/// executable).
fn preset_items(ui: &mut Ui, cmds: &mut Vec<Command>) {
    for (k, (name, file, _)) in SHIPPED.iter().enumerate() {
        if ui.button(*name).on_hover_text(*file).clicked() {
            cmds.push(Command::OpenPreset(k));
        }
    }
    #[cfg(not(target_arch = "wasm32"))]
    for (name, file) in crate::gui::model::presets::SHIPPED_WITH_FILES {
        if let Some(path) = crate::gui::model::presets::shipped_with_files_path(file)
            && ui
                .button(*name)
                .on_hover_text(path.display().to_string())
                .clicked()
        {
            cmds.push(Command::OpenPath(path));
        }
    }
}

/// The guided tour's presets.
fn guided_items(ui: &mut Ui, cmds: &mut Vec<Command>) {
    for (k, (name, file, _)) in crate::gui::model::presets::GUIDED.iter().enumerate() {
        if ui.button(*name).on_hover_text(*file).clicked() {
            cmds.push(Command::OpenGuided(k));
        }
    }
}

/// The exports.
fn export_items(ui: &mut Ui, st: &ToolbarStatus, cmds: &mut Vec<Command>) {
    let frames = ui.add_enabled(
        !st.exporting_frames,
        egui::Button::new("Animation frames (PNG)…"),
    );
    if frames
        .on_hover_text("numbered PNG frames of the scene view, for slides")
        .clicked()
    {
        cmds.push(Command::ExportFramesDialog);
    }
    if ui
        .button("Plots as PNG…")
        .on_hover_text(
            "the time plots (displacement, force, gap, contact) of the run so far, as one \
             figure with title, units and legends",
        )
        .clicked()
    {
        cmds.push(Command::ExportPngDialog);
    }
    if ui
        .add_enabled(st.patch, egui::Button::new("Contact patch heat map (PNG)…"))
        .on_hover_text(
            "a patch scene's contact force over its points now, as the patch view shows it",
        )
        .on_disabled_hover_text(
            "this scene's points are in one row: a heat map needs a patch, points in rows across the tread (e.g. presets/patch_texture.ron)",
        )
        .clicked()
    {
        cmds.push(Command::ExportHeatMapDialog);
    }
    let csv = ui.add_enabled(!st.exporting_csv, egui::Button::new("Run as CSV…"));
    if csv
        .on_hover_text("the run so far, every step, same columns as `tirecontact run`")
        .clicked()
    {
        cmds.push(Command::ExportCsvDialog);
    }
}

/// Classroom mode, the views and the mode bars.
fn view_items(ui: &mut Ui, st: &ToolbarStatus, cmds: &mut Vec<Command>) {
    // first, so that it stays reachable with classroom mode's large text
    classroom_toggle(ui, st, cmds);
    ui.separator();
    view_tabs(ui, st, cmds);
}

/// The classroom mode toggle; not on a phone, whose width its presenter
/// layout does not fit.
fn classroom_toggle(ui: &mut Ui, st: &ToolbarStatus, cmds: &mut Vec<Command>) {
    let wide = ui.ctx().content_rect().width() >= NARROW_PX;
    if ui
        .add_enabled(wide, egui::Button::selectable(st.classroom, "Classroom"))
        .on_hover_text("large fonts, scene and one plot, slow motion, contact phases labelled")
        .on_disabled_hover_text("classroom mode needs a window at least 700 px wide")
        .clicked()
    {
        cmds.push(Command::SetClassroom(!st.classroom));
    }
}

/// The views' tabs, the research tools' menu and the mode bars' toggle.
fn view_tabs(ui: &mut Ui, st: &ToolbarStatus, cmds: &mut Vec<Command>) {
    // the main views as tabs, the researcher tools in a menu
    // (the patch view, key 9, is a main view)
    let (tabs, tools) = View::ALL.split_at(3);
    let tools = &tools[..tools.len() - 1];
    for &v in tabs.iter().chain([&View::Patch]) {
        let key = View::ALL.iter().position(|&w| w == v).map_or(0, |k| k + 1);
        let r = ui
            .selectable_label(st.view == v, v.label())
            .on_hover_text(format!("key {key}"));
        if r.clicked() && (st.view != v || st.editing) {
            cmds.push(Command::ShowView(v));
        }
    }
    let current_tool = tools.iter().find(|&&v| v == st.view);
    let title = match current_tool {
        Some(v) => format!("Research: {}", v.label()),
        None => "Research".to_string(),
    };
    ui.menu_button(title, |ui| {
        for (k, &v) in tools.iter().enumerate() {
            let r = ui
                .selectable_label(st.view == v, v.label())
                .on_hover_text(format!("key {}", k + 4));
            if r.clicked() && (st.view != v || st.editing) {
                cmds.push(Command::ShowView(v));
            }
        }
    });
    ui.separator();
    // (a phone shows one view at a time: no room for the bars beside it)
    let roomy = ui.ctx().content_rect().width() >= NARROW_PX;
    if ui
        .add_enabled(
            roomy,
            egui::Button::selectable(st.mode_bars && roomy, "Mode bars"),
        )
        .on_hover_text("per-mode contributions to a point's displacement, with mute and solo")
        .on_disabled_hover_text(format!(
            "the mode bars need a window at least {NARROW_PX:.0} px wide, beside the view"
        ))
        .clicked()
    {
        cmds.push(Command::ShowModeBars(!st.mode_bars));
    }
}

/// Transport controls and the clock.
pub fn transport(ui: &mut Ui, st: &ToolbarStatus, cmds: &mut Vec<Command>) {
    // wrapped: in a narrow window (a phone) the clock goes to a second line
    ui.horizontal_wrapped(|ui| {
        let play = if st.playing { "Pause" } else { "Play" };
        if ui
            .button(RichText::new(play).strong())
            .on_hover_text(if st.playing {
                "pause the run (Space)"
            } else {
                "play the run from the current time (Space); a finished run starts again at t = 0"
            })
            .clicked()
        {
            cmds.push(Command::TogglePlay);
        }
        if ui
            .button("Step")
            .on_hover_text("one solver step (Right arrow)")
            .clicked()
        {
            cmds.push(Command::Step(1));
        }
        let id = Id::unique("tirecontact.n_steps");
        let mut n: u64 = ui.data(|d| d.get_temp(id)).unwrap_or(100);
        if ui
            .button("Step N")
            .on_hover_text("the number of solver steps in the field on the right, then pause")
            .clicked()
        {
            cmds.push(Command::Step(n));
        }
        ui.add(
            egui::DragValue::new(&mut n)
                .range(1..=10_000_000)
                .speed(10.0),
        )
        .accessible_name("N steps")
        .on_hover_text("how many solver steps Step N takes: 1 to 10 000 000 (drag or type)");
        ui.data_mut(|d| d.insert_temp(id, n));
        if ui
            .button("Reset")
            .on_hover_text("back to t = 0, paused; the edits are kept (R)")
            .clicked()
        {
            cmds.push(Command::Reset);
        }
        ui.separator();
        ui.label("speed");
        let mut speed = st.speed;
        egui::ComboBox::from_id_salt("tirecontact.speed")
            .selected_text(speed_text(speed))
            // every choice in view (egui's default 200 px hid the last one,
            // "as fast as possible", below a scroll); scrolls only in a
            // window too short for the list
            .height(speed_list_height(ui))
            .show_ui(ui, |ui| {
                for s in Speed::CHOICES {
                    ui.selectable_value(&mut speed, s, speed_text(s));
                }
            })
            .response
            .accessible_name("speed")
            .on_hover_text(
                "simulated time per wall-clock time: 0.001x (slow motion) to as fast as possible",
            );
        if speed != st.speed {
            cmds.push(Command::SetSpeed(speed));
        }
        ui.separator();
        ui.label(
            RichText::new(format!("t = {:.5} s", st.time_s))
                .monospace()
                .strong(),
        )
        .on_hover_text(format!("{} solver steps", st.steps));
        ui.label(format!("/ {} s", st.duration_s));
        let rt = if st.playing {
            format!("running at {}x real time", sig3(st.achieved_factor))
        } else {
            "paused".to_string()
        };
        // whole: wrapped, it broke into "running at 0.1x" and "real time";
        // as wide playing as paused, so that the row wraps the same way
        // either way (on a phone "paused" fitted the clock's line and
        // "running at …" took a line of its own: everything below jumped)
        let reserve_px = ui
            .painter()
            .layout_no_wrap(
                "running at 0.0123x real time".to_string(),
                egui::TextStyle::Body.resolve(ui.style()),
                egui::Color32::WHITE,
            )
            .size()
            .x;
        // a row of text where it wraps to one of its own (a phone): as high
        // as its text, not as a button
        let height = crate::gui::widgets::text_row_px(ui);
        if ui.available_size_before_wrap().x < reserve_px {
            ui.end_row();
            ui.set_row_height(height);
        }
        ui.allocate_ui_with_layout(
            egui::vec2(reserve_px, height),
            egui::Layout::left_to_right(egui::Align::Center),
            |ui| {
                ui.set_min_size(egui::vec2(reserve_px, height));
                ui.add(
                    egui::Label::new(RichText::new(rt).weak())
                        .wrap_mode(egui::TextWrapMode::Extend),
                );
            },
        );
    });
}

/// Height of the speed list: all its choices, at most most of the window.
fn speed_list_height(ui: &Ui) -> f32 {
    let row = ui
        .text_style_height(&egui::TextStyle::Button)
        .max(ui.spacing().interact_size.y)
        + ui.spacing().item_spacing.y
        + 2.0 * ui.spacing().button_padding.y;
    let all = row * Speed::CHOICES.len() as f32;
    all.min((ui.ctx().content_rect().height() - 80.0).max(100.0))
}

fn speed_text(s: Speed) -> String {
    match s {
        Speed::Factor(f) => format!("{}x real time", sig3(f)),
        Speed::Max => "as fast as possible".to_string(),
    }
}

/// Three significant digits, no trailing zeros.
pub fn sig3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return "0".to_string();
    }
    let d = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.d$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}
