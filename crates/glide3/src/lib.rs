//! glide3 (in progress)
