//! The gimbal angles' sines and cosines on a moving carrier, held between ticks: libm once
//! per dwell, a fine grid while a gimbal turns.

use crate::table::{GimbalAngles, GimbalFrame};
use crate::trig::{AngleTrig, GridTrig};

/// The gimbal angles' sines and cosines: held while the table dwells (libm once per dwell),
/// from a fine grid while it turns ([`GridTrig`]: no libm call in most ticks).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct GimbalTrig {
    outer: AngleTrig,
    pub(crate) inner: AngleTrig,
    outer_grid: GridTrig,
    inner_grid: GridTrig,
}

impl GimbalTrig {
    /// The gimbal frame at angles `a` while the table dwells (held for the next call).
    #[inline]
    pub(crate) fn frame(&mut self, a: GimbalAngles) -> GimbalFrame {
        GimbalFrame::from_sin_cos(self.outer.at(a.outer_rad), self.inner.at(a.inner_rad))
    }

    /// The gimbal frame at angles `a` in the middle of a tick on which the outer gimbal
    /// (`outer_turns`) or the inner one turns: the turning angle from the grid, the other held.
    #[inline]
    pub(crate) fn frame_turning(&mut self, a: GimbalAngles, outer_turns: bool) -> GimbalFrame {
        if outer_turns {
            GimbalFrame::from_sin_cos(
                self.outer_grid.sin_cos(a.outer_rad),
                self.inner.at(a.inner_rad),
            )
        } else {
            GimbalFrame::from_sin_cos(
                self.outer.at(a.outer_rad),
                self.inner_grid.sin_cos(a.inner_rad),
            )
        }
    }

    /// The gimbal frames at the tick's two quadrature points with angles `a`.
    #[inline]
    pub(crate) fn frames(&mut self, a: &[GimbalAngles; 2]) -> [GimbalFrame; 2] {
        if a[1] == a[0] {
            return [self.frame(a[0]); 2];
        }
        // Only the turning gimbal's angle differs between the points: the other's is held.
        let outer = if a[0].outer_rad == a[1].outer_rad {
            [self.outer.at(a[0].outer_rad); 2]
        } else {
            a.map(|a| self.outer_grid.sin_cos(a.outer_rad))
        };
        let inner = if a[0].inner_rad == a[1].inner_rad {
            [self.inner.at(a[0].inner_rad); 2]
        } else {
            a.map(|a| self.inner_grid.sin_cos(a.inner_rad))
        };
        [0, 1].map(|i| GimbalFrame::from_sin_cos(outer[i], inner[i]))
    }
}
