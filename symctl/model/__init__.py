"""Your own system: model files (TOML) read into a :class:`~symctl.model.modelfile.Model`."""
