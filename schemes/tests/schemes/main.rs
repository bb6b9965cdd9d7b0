//! rins-schemes against independent references: the verification's closed forms (Eq. 8,
//! Eq. 11, the static INS responses), the two integration methods against each other, and
//! identities of the physics that hold for any scheme.

mod closed_forms;
mod design;
mod files;
mod invariants;
mod simulation;
