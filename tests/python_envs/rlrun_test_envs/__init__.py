"""Gymnasium-API envs written in Python for rlrun's tests of its Python env bridge
(src/rlrun/envs/python/). They use only numpy: the spaces below have the attributes of
gymnasium.spaces (Box, Discrete, ...), which is all rlrun reads, so the tests run where
gymnasium is not installed (Debian has no package of it)."""
