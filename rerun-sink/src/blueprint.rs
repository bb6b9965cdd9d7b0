//! The default layout: the 3D table and the dwell log on the left, tabs of time series on the
//! right (IMU output, table and temperatures, effects, navigation, results, about).

use anyhow::Result;
use rerun::RecordingStream;
use rerun::blueprint::{
    Blueprint, BlueprintActivation, ContainerLike, Horizontal, Spatial3DView, Tabs,
    TextDocumentView, TextLogView, TimeSeriesView, Vertical,
};

/// What the recording holds, so the blueprint shows only views that have data.
#[derive(Clone, Debug, Default)]
pub struct Layout {
    /// A plant run: 3D table, IMU output, gimbal, temperatures, effects.
    pub plant: bool,
    /// Navigation cases logged under `nav/<case>/`.
    pub nav_cases: Vec<String>,
    /// Further time-series tabs: (tab name, entity roots, one view per root).
    pub extra: Vec<(String, Vec<String>)>,
    /// Markdown documents to show (entity paths).
    pub docs: Vec<String>,
    /// A moving carrier: a 3D view of its track (`track`, local ENU around the start, m).
    pub track: bool,
}

fn series(name: &str, origin: &str) -> TimeSeriesView {
    TimeSeriesView::new(name).with_origin(origin)
}

fn vertical(name: &str, views: Vec<ContainerLike>) -> ContainerLike {
    Vertical::new(views).with_name(name).into()
}

/// Builds the blueprint for `layout` and sends it as the recording's default.
pub fn send(rec: &RecordingStream, layout: &Layout) -> Result<()> {
    let mut tabs: Vec<ContainerLike> = Vec::new();
    if layout.plant {
        tabs.push(vertical(
            "IMU output",
            ["x", "y", "z"]
                .iter()
                .map(|a| {
                    series(
                        &format!("Δθ {a} per sample (rad)"),
                        &format!("/imu/dtheta_rad/{a}"),
                    )
                    .into()
                })
                .chain(["x", "y", "z"].iter().map(|a| {
                    series(
                        &format!("Δv {a} per sample (m/s)"),
                        &format!("/imu/dv_mps/{a}"),
                    )
                    .into()
                }))
                .collect(),
        ));
        tabs.push(vertical(
            "Table and temperatures",
            vec![
                series("outer gimbal (deg)", "/gimbal/outer_deg").into(),
                series("inner gimbal (deg)", "/gimbal/inner_deg").into(),
                series("node temperatures (°C)", "/thermal").into(),
            ],
        ));
        tabs.push(vertical(
            "Effects",
            vec![
                series("gyro effect contributions (deg/h)", "/effects/gyro").into(),
                series("accelerometer effect contributions (µg)", "/effects/accel").into(),
            ],
        ));
    }
    for case in &layout.nav_cases {
        tabs.push(vertical(
            &format!("Navigation: {case}"),
            [
                ("attitude error (deg)", "attitude_error_deg"),
                ("velocity error (m/s)", "velocity_error_mps"),
                ("position error (nmi)", "position_error_nmi"),
                ("tRMS (nmi, Eq. 20)", "trms_nmi"),
            ]
            .iter()
            .map(|(n, q)| series(n, &format!("/nav/{case}/{q}")).into())
            .collect(),
        ));
    }
    for (name, roots) in &layout.extra {
        tabs.push(vertical(
            name,
            roots
                .iter()
                .map(|r| series(r.trim_start_matches('/'), r).into())
                .collect(),
        ));
    }
    for d in &layout.docs {
        tabs.push(
            TextDocumentView::new(d.trim_start_matches('/'))
                .with_origin(d.as_str())
                .into(),
        );
    }
    let right: ContainerLike = Tabs::new(tabs).into();
    let root: ContainerLike = if layout.plant {
        let mut views: Vec<ContainerLike> = vec![
            Spatial3DView::new("IMU on the dual-axis table")
                .with_origin("/world")
                .into(),
        ];
        let mut shares = vec![3.0, 1.0];
        if layout.track {
            views.push(
                Spatial3DView::new("carrier track (ENU around the start, m)")
                    .with_origin("/track")
                    .into(),
            );
            shares = vec![3.0, 2.0, 1.0];
        }
        views.push(
            TextLogView::new("dwell positions")
                .with_origin("/status")
                .into(),
        );
        let left: ContainerLike = Vertical::new(views).with_row_shares(shares).into();
        Horizontal::new([left, right])
            .with_column_shares([2.0, 3.0])
            .into()
    } else {
        right
    };
    Blueprint::new(root).send(rec, BlueprintActivation::default())?;
    Ok(())
}
