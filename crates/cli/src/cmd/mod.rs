//! One module per subcommand.

pub mod dynamics;
pub mod robot;
