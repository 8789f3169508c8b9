//! The palette: calm neutrals, one dark ink for the arm, soft hues for paths, red for the goal.

/// Behind everything.
pub(crate) const PAGE: &str = "#fbfaf7";
/// Inside the plot area.
pub(crate) const PLOT: &str = "#ffffff";
/// The plot area's border.
pub(crate) const FRAME: &str = "#d9dde3";
/// Grid lines at tick positions.
pub(crate) const GRID: &str = "#e7eaee";
/// Grid lines between ticks.
pub(crate) const GRID_MINOR: &str = "#f3f4f6";
/// The x = 0 and y = 0 lines.
pub(crate) const AXIS: &str = "#c3c9d1";
/// Tick labels and other quiet text.
pub(crate) const MUTED_TEXT: &str = "#6b7280";
/// Captions and titles.
pub(crate) const TEXT: &str = "#374151";
/// Reachable cells: the playground's green at a fifth of its strength.
pub(crate) const WORKSPACE: &str = "#dceae1";
/// Reach circles.
pub(crate) const REACH: &str = "#5f9e77";
/// The arm, its ghosts and its base.
pub(crate) const INK: &str = "#26324a";
/// The mount under the base.
pub(crate) const MOUNT: &str = "#cdd5e0";
/// The goal: a clear red (the tests look for it).
pub(crate) const GOAL: &str = "#d62728";
/// A pinned effector (held where it is): a filled square.
pub(crate) const PIN: &str = "#2b6cb0";
/// Paths of the joints between base and tip, cycled.
pub(crate) const JOINT_HUES: [&str; 5] = ["#4e79a7", "#76b7b2", "#b07aa1", "#9c755f", "#8cb369"];
/// Path of the tip.
pub(crate) const TIP_HUE: &str = "#ec7f2d";

/// The palette's colours by role, for callers that draw with it too (the playground page gets
/// them from `GET /api/meta`, so its screen, its downloads and the CLI's pictures agree; it
/// serialises by these field names, which the page's `COLORS` uses).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Colours {
    /// Inside the plot area.
    pub plot: &'static str,
    /// Grid lines.
    pub grid: &'static str,
    /// The x = 0 and y = 0 lines.
    pub axis: &'static str,
    /// Tick labels.
    pub label: &'static str,
    /// The arm, its ghosts and its base.
    pub ink: &'static str,
    /// Reach circles.
    pub reach: &'static str,
    /// Reachable cells.
    pub workspace: &'static str,
    /// The goal.
    pub goal: &'static str,
    /// The tip's path.
    pub path: &'static str,
    /// The paths of the other joints, cycled from the first joint after the base.
    pub joints: [&'static str; 5],
}

/// The palette.
pub const COLOURS: Colours = Colours {
    plot: PLOT,
    grid: GRID,
    axis: AXIS,
    label: MUTED_TEXT,
    ink: INK,
    reach: REACH,
    workspace: WORKSPACE,
    goal: GOAL,
    path: TIP_HUE,
    joints: JOINT_HUES,
};

/// The colour of the path of joint `k` (1-based; `n` is the tip).
pub(crate) fn joint_hue(k: usize, n: usize) -> &'static str {
    if k == n { TIP_HUE } else { JOINT_HUES[(k.saturating_sub(1)) % JOINT_HUES.len()] }
}

/// The thin border around a plot area, drawn over its contents.
pub(crate) fn plot_frame(svg: &mut crate::svg::Svg, plot: &crate::view::PixelRect, unit: f64) {
    let attrs = format!("fill=\"none\" stroke=\"{FRAME}\" stroke-width=\"{}\"", crate::svg::num(unit.max(0.6)));
    svg.rect(plot.left, plot.top, plot.width(), plot.height(), &attrs);
}

/// `#rrggbb` as bytes.
pub(crate) fn rgb(hex: &str) -> [u8; 3] {
    let byte = |i: usize| u8::from_str_radix(hex.get(i..i + 2).unwrap_or("00"), 16).unwrap_or(0);
    [byte(1), byte(3), byte(5)]
}

/// Every solid colour of the palette: a GIF keeps these exact, whatever the quantiser learns.
pub(crate) fn key_colours() -> Vec<[u8; 3]> {
    let mut v: Vec<[u8; 3]> =
        [PAGE, PLOT, FRAME, GRID, GRID_MINOR, AXIS, MUTED_TEXT, TEXT, WORKSPACE, REACH, INK, MOUNT, GOAL, TIP_HUE]
            .iter()
            .chain(JOINT_HUES.iter())
            .map(|h| rgb(h))
            .collect();
    v.push([255, 255, 255]);
    v.sort_unstable();
    v.dedup();
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_parses() {
        assert_eq!(rgb(GOAL), [0xd6, 0x27, 0x28]);
        assert!(key_colours().contains(&[0xd6, 0x27, 0x28]));
        assert_eq!(joint_hue(3, 3), TIP_HUE);
        assert_eq!(joint_hue(1, 3), JOINT_HUES[0]);
        assert_eq!(joint_hue(7, 9), JOINT_HUES[1]);
    }
}
