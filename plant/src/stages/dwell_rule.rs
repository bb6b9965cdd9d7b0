//! How much of a held dwell's interval the plant may keep: the sensor-error stage's answer,
//! from what each switched-on term, catalogue and declared, says about the dwell.

/// What the plant may reuse of one interval of a held dwell (the table still on the static
/// carrier, no thermal update) for the next: the union of the catalogue terms'
/// [`crate::effects::DwellDependence`] and the declared effects' `varies_in_dwell`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum DwellRule {
    /// Every switched-on term gives the same bits each tick of the dwell: the interval again,
    /// whole.
    ReuseWhole,
    /// Only declared effects change within the dwell (they read the time or a motion clock, or
    /// have memory): the catalogue's errors and the true increments are kept, the declared
    /// part is redone tick by tick.
    RedoDeclared,
    /// A catalogue term changes within the dwell: nothing is kept, every tick is worked out.
    /// The redo path keeps the catalogue's errors, so it would be wrong here.
    WorkEveryTick,
}
