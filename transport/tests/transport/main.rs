//! The integration tests of rins-transport in one test binary (one link instead of one per
//! file): one module per former test file; `ship` is the ship scenario the transport tests share,
//! `peer` drives the `rins-chaos-peer` processes of the chaos and start-order tests. Sessions are
//! named by the test's process id and a prefix of each module's own (c, t, d, iso, o, tr).

mod peer;
mod ship;

mod chaos;
mod contracts;
mod defects;
mod isolation_command;
mod start_order;
mod truth;
