//! dhgen's symbolic engine.
