"""F´ wire and file formats: packets, file packets, framings, sequence files."""
