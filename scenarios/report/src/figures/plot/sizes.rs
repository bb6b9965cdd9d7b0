//! Print sizes: the figure's width and panel height, text sizes at one column width, and the
//! drawn size of marks.

use crate::figures::rules;

/// Figure width, px: printed at [`rules::PRINT_WIDTH_IN`] (3.5 in, one journal column) that is
/// 257 px/in.
pub const WIDTH_PX: u32 = 900;
/// Height of one panel, px.
pub const PANEL_PX: u32 = 440;
/// Pixels per envelope column: a long series gets one min/max/mean column per this many.
pub const COLUMN_PX: i32 = 2;
/// Size of tick labels, axis labels, legend and category names at print width, pt.
pub const TEXT_PT: f64 = rules::MIN_TEXT_PT;
/// Size of a panel's title at print width, pt.
pub const CAPTION_PT: f64 = 9.0;
/// Size of the figure's title at print width, pt.
pub const TITLE_PT: f64 = 10.0;
/// Radius of the dot at a bar's estimate, px.
pub const BAR_DOT_PX: i32 = 6;
