//! One module per subcommand.

pub mod dynamics;
pub mod lwpr;
pub mod reproduce;
pub mod robot;
pub mod simulate;
pub mod toy;
