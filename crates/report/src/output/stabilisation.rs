//! The stabilisation diagram as a figure panel, for LSCE (method §6.3) and
//! LSCF (method §6.5.1) alike: the diagram's poles at their frequency and
//! model order, one marker per category ([`Stability`]), and the poles the
//! identification chose ringed at the chosen order.

use super::figures::{Panel, Series, Style};
use tirecontact_core::model::stability::{DiagramOrder, Stability, points_of};

/// The identification method a diagram comes from: it names the panel,
/// the order axis, the shape compared between orders and the chosen poles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Time domain, model order `M` in pole pairs, residue MAC.
    Lsce,
    /// Frequency domain, polynomial order `p`, participation-vector MAC.
    Lscf,
}

impl Method {
    fn title(self) -> &'static str {
        match self {
            Method::Lsce => "LSCE stabilisation diagram",
            Method::Lscf => "poles by polynomial order",
        }
    }

    fn order_axis(self) -> &'static str {
        match self {
            Method::Lsce => "model order M (pole pairs)",
            Method::Lscf => "polynomial order p",
        }
    }

    /// The shape whose MAC makes a pole [`Stability::Stable`].
    fn shape(self) -> &'static str {
        match self {
            Method::Lsce => "MAC",
            Method::Lscf => "vector",
        }
    }

    fn chosen(self, order: usize) -> String {
        match self {
            Method::Lsce => format!("selected order {order}"),
            Method::Lscf => format!("kept at order {order}"),
        }
    }
}

/// A category's legend entry, marker and palette colour.
fn marker(stability: Stability, method: Method) -> (String, Style, usize) {
    match stability {
        Stability::Stable => (
            format!("stable: f, xi, {}", method.shape()),
            Style::Markers(5),
            2,
        ),
        Stability::FrequencyDamping => ("stable: f, xi".into(), Style::HollowMarkers(5), 0),
        Stability::Frequency => ("stable: f".into(), Style::HollowMarkers(4), 4),
        Stability::New => ("new / not stable".into(), Style::HollowMarkers(2), 8),
        Stability::Damped => (
            "damping above the limit (not a mode)".into(),
            Style::HollowMarkers(2),
            3,
        ),
    }
}

/// The stabilisation diagram of `method`: every pole of `diagram` marked
/// by its category, most stable first, then the chosen poles (frequencies
/// `chosen_hz`, Hz) ringed at `chosen_order`.
pub fn panel(
    diagram: &[DiagramOrder],
    method: Method,
    chosen_order: usize,
    chosen_hz: &[f64],
) -> Panel {
    let mut series: Vec<Series> = Stability::ALL
        .iter()
        // over-damped poles have a series only when the diagram draws some
        .filter(|&&s| s != Stability::Damped || points_of(diagram, s).next().is_some())
        .map(|&stability| {
            let (name, style, color) = marker(stability, method);
            Series {
                name,
                points: points_of(diagram, stability).collect(),
                style,
                color: Some(color),
            }
        })
        .collect();
    series.push(Series {
        name: method.chosen(chosen_order),
        points: chosen_hz
            .iter()
            .map(|&f| (f, chosen_order as f64))
            .collect(),
        style: Style::HollowMarkers(9),
        color: Some(6),
    });
    Panel {
        title: method.title().into(),
        x_label: "frequency (Hz)".into(),
        y_label: method.order_axis().into(),
        series,
        ..Panel::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tirecontact_core::model::stability::DiagramPole;

    #[test]
    fn every_category_has_its_series_and_the_chosen_poles_come_last() {
        let pole = |freq_hz, stability| DiagramPole {
            freq_hz,
            damping_ratio: 0.02,
            stability,
        };
        let diagram = vec![
            DiagramOrder {
                order: 1,
                poles: vec![pole(10.0, Stability::New)],
            },
            DiagramOrder {
                order: 2,
                poles: vec![pole(10.0, Stability::Stable), pole(30.0, Stability::New)],
            },
        ];
        let p = panel(&diagram, Method::Lscf, 2, &[10.0]);
        let names: Vec<&str> = p.series.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "stable: f, xi, vector",
                "stable: f, xi",
                "stable: f",
                "new / not stable",
                "kept at order 2"
            ]
        );
        assert_eq!(p.series[0].points, [(10.0, 2.0)]);
        assert_eq!(p.series[3].points, [(10.0, 1.0), (30.0, 2.0)]);
        assert_eq!(p.series[4].points, [(10.0, 2.0)]);
        assert_eq!(p.y_label, "polynomial order p");
    }
}
