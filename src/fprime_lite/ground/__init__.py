"""The ground's side of the downlink: decoding packets, the run's logs and downlinked files."""
