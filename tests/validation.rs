//! Analytic validation of the reference model (MODEL.md section 12).
