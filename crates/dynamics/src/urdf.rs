//! URDF import and export.
