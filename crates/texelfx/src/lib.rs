//! texelfx (in progress)
