//! One module per subcommand; no command imports another.

pub mod adapt;
pub mod bench;
pub mod dynamics;
pub mod eval;
pub mod lwpr;
pub mod report;
pub mod reproduce;
pub mod robot;
pub mod simulate;
pub mod toy;
pub mod train;
