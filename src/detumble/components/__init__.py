"""The PROVES detumble flight components and their F´ types."""
