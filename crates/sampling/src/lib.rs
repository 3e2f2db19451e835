//! Random numbers and sample mappings for Monte Carlo rendering.
