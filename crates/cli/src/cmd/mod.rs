//! One module per subcommand.

pub mod dynamics;
pub mod robot;
pub mod lwpr;
pub mod toy;
pub mod simulate;
