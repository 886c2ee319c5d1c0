"""Device knowledge from the manuals, in one place per device: register
maps, bit meanings, data types, codes with their texts, and the small codecs
that turn manual tables into bytes. Pure: no bus, no threads. The drivers,
the simulators, the EDS files and the vendor function blocks all take their
numbers from here."""
