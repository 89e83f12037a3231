#![doc = include_str!("../README.md")]

pub mod csv;
pub mod e8;
mod error;
mod family;
pub mod figures;
pub mod folder;
pub mod page;
pub mod plot;
pub mod runs;
mod safety;
pub mod series;
mod summary;

pub use error::{ReportError, Result};
pub use folder::{render, write_data, write_report, Page};
