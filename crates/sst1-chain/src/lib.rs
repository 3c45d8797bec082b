//! sst1-chain (in progress)
