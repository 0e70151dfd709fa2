"""The HTML report of `ccopt run` and the plots it embeds."""
