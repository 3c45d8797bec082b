//! C ABI for Glide 3 (in progress)
