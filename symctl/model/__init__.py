"""Your own system: model files (TOML) read into a :class:`~symctl.model.modelfile.Model`.

``schema`` (the table of fields), ``source`` (the text, its lines, unknown keys),
``units`` (units checked where given), ``modelfile`` (the reader) and
``presets`` (the paper's muscle as a model file).
"""
