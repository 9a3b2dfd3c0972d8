"""The stages of loading a topology YAML file; :func:`fprime_lite.deploy.topology_loader.load_topology`
runs them: ``parse`` (and ``files``) → ``schema`` → ``build`` → ``wire``; ``problems`` collects what
each finds."""
