"""Quality control of instrument records: QARTOD-style tests, Goring-Nikora despiking, flags,
masking and gap filling, and checks of the metadata against the records."""
