//! Numbers, names and file locations as error messages echo them: the `rins-message` crate,
//! re-exported under the plant's path (the FMI layer uses the same crate).

pub use rins_message::*;
