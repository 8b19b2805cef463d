"""Result files of any length: chunks, formats, partial files."""
