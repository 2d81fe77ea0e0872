"""Reporting: the figure registry, the claims ledger, the gallery, the house style, the explorer and
`make figures`."""
