"""Building and running deployments: the scheduler, topologies and their YAML, the dictionary."""
