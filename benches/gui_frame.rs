//! One visualiser frame on the CPU (`cargo bench --bench gui_frame`): the
//! solver steps of 1/60 s at 1x real time, building the UI and tessellating
//! it, without rasterisation (the GPU's part, or llvmpipe's under Xvfb).
//! Scenes: the paper preset (time plots and scene view) and 50 points x 20
//! modes, each played for 2 s first so the plots are full. Frame rates are
//! 1 / these times at most; the README reports them beside the measured
//! frame rate under Xvfb.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use tirecontact::analysis::bench::scenes::many_points;
use tirecontact::gui::model::command::View;
use tirecontact::gui::{App, Command};
use tirecontact::{DEFAULT_PRESET, DEFAULT_PRESET_NAME, Scene};

const FRAME_S: f64 = 1.0 / 60.0;

struct Driver {
    ctx: egui::Context,
    app: App,
    t_s: f64,
}

impl Driver {
    fn new(mut scene: Scene, view: View) -> Self {
        scene.duration_s = 1e4;
        let mut app = App::new(scene, None).expect("bench scene builds");
        app.apply(Command::ShowView(view));
        app.apply(Command::Play);
        let mut d = Driver {
            ctx: egui::Context::default(),
            app,
            t_s: 0.0,
        };
        for _ in 0..120 {
            d.frame();
        }
        d
    }

    /// One frame: returns the number of tessellated meshes.
    fn frame(&mut self) -> usize {
        self.t_s += FRAME_S;
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(1500.0, 950.0),
            )),
            time: Some(self.t_s),
            predicted_dt: FRAME_S as f32,
            ..Default::default()
        };
        let app = &mut self.app;
        let out = self.ctx.run_ui(input, |ui| app.show(ui));
        self.ctx.tessellate(out.shapes, out.pixels_per_point).len()
    }
}

fn frames(c: &mut Criterion) {
    let paper = Scene::parse(DEFAULT_PRESET, DEFAULT_PRESET_NAME).expect("embedded preset");
    let cases = [
        ("paper/time_plots", paper.clone(), View::TimePlots),
        ("paper/scene_view", paper, View::Scene),
        ("50x20/time_plots", many_points(50, 20), View::TimePlots),
    ];
    let mut group = c.benchmark_group("gui_frame");
    group.sample_size(30);
    for (name, scene, view) in cases {
        let mut d = Driver::new(scene, view);
        group.bench_function(name, |b| b.iter(|| black_box(d.frame())));
        assert!(d.app.time_control().is_playing(), "{name}: the run stopped");
    }
    group.finish();
}

criterion_group!(benches, frames);
criterion_main!(benches);
