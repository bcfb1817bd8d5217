//! The scene's contact points: a list of `Point(...)`, or a grid over the
//! contact patch written `Grid(...)` and saved back as written.

use super::{MAX_POINTS, Point};
use serde::de::{self, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::ops::{Deref, DerefMut};

/// How a grid's points are pressed into the road: their undeformed heights.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Preload {
    /// Every point `depth_m` (m, >= 0) below the mean road plane:
    /// `h = -depth_m`.
    Flat { depth_m: f64 },
    /// A footprint parabolic along the rolling direction:
    /// `h(x) = -depth_m (1 - (2 x / length_m)²)`; points beyond
    /// `|x| = length_m / 2` are above the road.
    Parabolic { depth_m: f64, length_m: f64 },
}

/// A grid of contact points over the patch, centred on `(0, 0)`: `along`
/// points along the rolling direction `spacing_m.0` apart, in `across` rows
/// `spacing_m.1` apart. Point `j along + i` (row `j` across, `i` along) is
/// at `x = (i - (along - 1)/2) Δx`, `y = (j - (across - 1)/2) Δy`: points
/// run along the rolling direction within each row across.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename = "Grid", deny_unknown_fields)]
pub struct PointGrid {
    /// Points along the rolling direction, >= 1.
    pub along: usize,
    /// Rows across the tread, >= 1.
    pub across: usize,
    /// Spacing `(Δx, Δy)` along and across (m), > 0.
    pub spacing_m: (f64, f64),
    /// The undeformed heights.
    pub preload: Preload,
}

impl PointGrid {
    /// What is wrong with the grid's fields: `(field, value, expected)`.
    pub fn check(&self) -> Option<(String, String, String)> {
        let bad = |f: &str, v: String, e: &str| Some((format!("points.{f}"), v, e.to_string()));
        if self.along == 0 {
            return bad(
                "along",
                "0".into(),
                &format!("1 to {MAX_POINTS} points along"),
            );
        }
        if self.across == 0 {
            return bad(
                "across",
                "0".into(),
                &format!("1 to {MAX_POINTS} rows across"),
            );
        }
        if self.along.saturating_mul(self.across) > MAX_POINTS {
            // the field of the larger count: the one most likely mistyped
            let (field, room) = if self.along >= self.across {
                ("along", MAX_POINTS / self.across)
            } else {
                ("across", MAX_POINTS / self.along)
            };
            return bad(
                field,
                format!("{} × {}", self.along, self.across),
                &format!(
                    "at most {MAX_POINTS} points in all: 1 to {room} {field} with {} {}",
                    if field == "along" {
                        self.across
                    } else {
                        self.along
                    },
                    if field == "along" {
                        "rows across"
                    } else {
                        "points along"
                    }
                ),
            );
        }
        for (k, v) in [self.spacing_m.0, self.spacing_m.1].into_iter().enumerate() {
            if !(v.is_finite() && v > 0.0) {
                return bad(&format!("spacing_m.{k}"), v.to_string(), "a spacing > 0 m");
            }
        }
        let (depth, length) = match self.preload {
            Preload::Flat { depth_m } => (depth_m, None),
            Preload::Parabolic { depth_m, length_m } => (depth_m, Some(length_m)),
        };
        if !(depth.is_finite() && (0.0..=1.0).contains(&depth)) {
            return bad(
                "preload.depth_m",
                depth.to_string(),
                "a press depth from 0 to 1 m",
            );
        }
        if let Some(l) = length
            && !(l.is_finite() && l > 0.0)
        {
            return bad(
                "preload.length_m",
                l.to_string(),
                "a footprint length > 0 m",
            );
        }
        None
    }

    /// The grid's points, in order (the fields checked).
    pub fn points(&self) -> Vec<Point> {
        let (dx, dy) = self.spacing_m;
        let mid = |n: usize| 0.5 * (n as f64 - 1.0);
        (0..self.across)
            .flat_map(|j| {
                (0..self.along).map(move |i| {
                    let x_m = (i as f64 - mid(self.along)) * dx;
                    let y_m = (j as f64 - mid(self.across)) * dy;
                    let h_m = match self.preload {
                        Preload::Flat { depth_m } => -depth_m,
                        Preload::Parabolic { depth_m, length_m } => {
                            let u = 2.0 * x_m / length_m;
                            -depth_m * (1.0 - u * u)
                        }
                    };
                    // +0.0 on the centreline (not -0.0): saved as omitted
                    Point {
                        x_m: x_m + 0.0,
                        y_m: y_m + 0.0,
                        h_m,
                    }
                })
            })
            .collect()
    }
}

/// What a `Grid(...)` or, by mistake, a single `Point(...)` may hold: read
/// first, so that a lone point is told apart from a grid.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GridOrPoint {
    #[serde(default)]
    along: Given<usize>,
    #[serde(default)]
    across: Given<usize>,
    #[serde(default)]
    spacing_m: Given<(f64, f64)>,
    #[serde(default)]
    preload: Given<Preload>,
    #[serde(default)]
    x_m: Given<f64>,
    #[serde(default)]
    y_m: Given<f64>,
    #[serde(default)]
    h_m: Given<f64>,
}

/// A field read as written (RON would want `Some(...)` for an `Option`).
struct Given<T>(Option<T>);

impl<T> Default for Given<T> {
    fn default() -> Self {
        Given(None)
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Given<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        T::deserialize(d).map(|v| Given(Some(v)))
    }
}

/// The contact points: the list the solver uses, and the grid it was
/// written as (kept while the list is not edited, so a save writes the
/// `Grid(...)` form back). Reads as a `Vec<Point>`; any mutable access
/// drops the grid form.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Points {
    list: Vec<Point>,
    grid: Option<PointGrid>,
}

impl Points {
    /// The points of a grid; none when [`PointGrid::check`] refuses it
    /// (`Scene::validate` then names the field).
    pub fn from_grid(grid: PointGrid) -> Self {
        // a grid refused by its check has no points (a count typed by
        // mistake must not allocate billions): validation names its field
        let list = if grid.check().is_none() {
            grid.points()
        } else {
            Vec::new()
        };
        Points {
            list,
            grid: Some(grid),
        }
    }

    /// The grid the points were written as, if they were not edited since.
    pub fn grid(&self) -> Option<&PointGrid> {
        self.grid.as_ref()
    }
}

impl From<Vec<Point>> for Points {
    fn from(list: Vec<Point>) -> Self {
        Points { list, grid: None }
    }
}

impl Deref for Points {
    type Target = Vec<Point>;
    fn deref(&self) -> &Vec<Point> {
        &self.list
    }
}

impl DerefMut for Points {
    fn deref_mut(&mut self) -> &mut Vec<Point> {
        self.grid = None;
        &mut self.list
    }
}

impl<'a> IntoIterator for &'a Points {
    type Item = &'a Point;
    type IntoIter = std::slice::Iter<'a, Point>;
    fn into_iter(self) -> Self::IntoIter {
        self.list.iter()
    }
}

impl Serialize for Points {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match &self.grid {
            Some(g) => g.serialize(s),
            None => self.list.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Points {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Points;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a list of Point(x_m: …, h_m: …) or Grid(along: …, across: …, spacing_m: (…, …), preload: …)")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Points, A::Error> {
                let mut list = Vec::new();
                // (the count is validated with the scene: its file is bounded)
                while let Some(p) = seq.next_element::<Point>()? {
                    list.push(p);
                }
                Ok(list.into())
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Points, A::Error> {
                let any = GridOrPoint::deserialize(de::value::MapAccessDeserializer::new(map))?;
                if any.x_m.0.is_some() || any.y_m.0.is_some() || any.h_m.0.is_some() {
                    return Err(de::Error::custom(
                        "Expected opening `[` of a list of points: found one Point(...); write points: [Point(...), ...], or a Grid(...)",
                    ));
                }
                let missing = |f: &'static str| de::Error::missing_field(f);
                let grid = PointGrid {
                    along: any.along.0.ok_or_else(|| missing("along"))?,
                    across: any.across.0.ok_or_else(|| missing("across"))?,
                    spacing_m: any.spacing_m.0.ok_or_else(|| missing("spacing_m"))?,
                    preload: any.preload.0.ok_or_else(|| missing("preload"))?,
                };
                if let Some((field, value, expected)) = grid.check() {
                    return Err(de::Error::custom(format!(
                        "{field} = {value}: expected {expected}"
                    )));
                }
                Ok(Points::from_grid(grid))
            }
        }
        d.deserialize_any(V)
    }
}

impl<'a> IntoIterator for &'a mut Points {
    type Item = &'a mut Point;
    type IntoIter = std::slice::IterMut<'a, Point>;
    fn into_iter(self) -> Self::IntoIter {
        self.deref_mut().iter_mut()
    }
}

impl FromIterator<Point> for Points {
    fn from_iter<I: IntoIterator<Item = Point>>(iter: I) -> Self {
        Vec::from_iter(iter).into()
    }
}

#[cfg(test)]
mod tests {

    use crate::scene::Scene;

    fn scene_text(points: &str) -> String {
        format!(
            r#"Scene(
    name: "grid",
    tyre: Plate(),
    points: {points},
    road: Sine(amplitude_m: 0.0005, wavelength_m: 0.1),
    speed_mps: 10.0,
    ramp_s: 0.001,
    dt_s: 1e-5,
    duration_s: 0.001,
    contact: Compliant(stiffness_n_m: [2e5]),
)"#
        )
    }

    #[test]
    fn a_grid_expands_along_within_rows_across_and_saves_as_written() {
        let text = scene_text(
            "Grid(along: 3, across: 2, spacing_m: (0.01, 0.02), preload: Parabolic(depth_m: 0.002, length_m: 0.04))",
        );
        let s = Scene::parse(&text, "grid.ron").unwrap();
        let p: Vec<(f64, f64, f64)> = s.points.iter().map(|p| (p.x_m, p.y_m, p.h_m)).collect();
        let h = |x: f64| -0.002 * (1.0 - (2.0 * x / 0.04f64).powi(2));
        let want = [
            (-0.01, -0.01, h(-0.01)),
            (0.0, -0.01, h(0.0)),
            (0.01, -0.01, h(0.01)),
            (-0.01, 0.01, h(-0.01)),
            (0.0, 0.01, h(0.0)),
            (0.01, 0.01, h(0.01)),
        ];
        assert_eq!(p.len(), want.len());
        for (a, b) in p.iter().zip(want) {
            assert!(
                (a.0 - b.0).abs() < 1e-15 && (a.1 - b.1).abs() < 1e-15 && (a.2 - b.2).abs() < 1e-15,
                "{a:?} vs {b:?}"
            );
        }
        // saved in the Grid form, and read back to the same scene
        let saved = s.to_ron_string();
        assert!(saved.contains("points: Grid("), "{saved}");
        assert!(!saved.contains("Point("), "{saved}");
        assert_eq!(Scene::parse(&saved, "saved.ron").unwrap(), s);
        // an edited point drops the grid form: the list is saved
        let mut edited = s.clone();
        edited.points[4].h_m = -0.003;
        assert!(edited.points.grid().is_none());
        let saved = edited.to_ron_string();
        assert!(
            saved.contains("Point(") && !saved.contains("Grid("),
            "{saved}"
        );
        assert_eq!(
            Scene::parse(&saved, "edited.ron").unwrap().points[4].h_m,
            -0.003
        );
    }

    #[test]
    fn bad_grids_are_refused_naming_the_field_and_place() {
        for (grid, want) in [
            (
                "Grid(along: 0, across: 2, spacing_m: (0.01, 0.01), preload: Flat(depth_m: 0.001))",
                "points.along = 0: expected 1 to 2000 points along",
            ),
            (
                "Grid(along: 3, across: 2, spacing_m: (0.01, -1.0), preload: Flat(depth_m: 0.001))",
                "points.spacing_m.1 = -1: expected a spacing > 0 m",
            ),
            (
                "Grid(along: 300, across: 20, spacing_m: (0.01, 0.01), preload: Flat(depth_m: 0.001))",
                "at most 2000 points",
            ),
            (
                "Grid(along: 3, across: 2, spacing_m: (0.01, 0.01), preload: Flat(depth_m: -0.001))",
                "points.preload.depth_m = -0.001",
            ),
            (
                "Grid(along: 3, acros: 2, spacing_m: (0.01, 0.01), preload: Flat(depth_m: 0.001))",
                "acros",
            ),
        ] {
            let e = Scene::parse(&scene_text(grid), "g.ron")
                .unwrap_err()
                .to_string();
            assert!(e.contains(want), "{grid}: {e}");
            assert!(e.contains("g.ron:4:"), "{grid}: no line in {e}");
        }
    }
}
