"""The value domain shared by the language and the net: colour sets and multisets."""
