//! pixelfx (in progress)
