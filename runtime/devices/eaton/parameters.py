"""Eaton PowerXL parameters: Tabellen 20-24 as printed, and the Modbus register of a parameter number.

Source: manual 002 (shared/manuals/002_a23ab2a6587941cb.txt, "L<n>" a line of
that file) and its digest (shared/digests/002_eaton_modbus.md, "§" and the
ambiguities "A<n>"). The P0 display values that have a register are
registers.MONITOR_VALUES.

    parameter_register(Family.DA1, "P1-01")   -> 101
    parameter_register(Family.DC1, "P-36")    -> 164
    parameter_rows(Family.DC1, "P-36")        -> the three fields of register 164

Parameter names are the manual's German designations, as printed; the
numbers and everything the runtime acts on have English names.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass

from .registers import Family, Scale

# ---------------------------------------------------------------------------
# Parameters (Tabellen 20-24, L1178-1974)
# ---------------------------------------------------------------------------

# When a parameter may be written ("Zugriff", columns rw/ro and RUN/STOP)
RUN = "RUN"  # rw, also while the drive runs
STOP = "STOP"  # rw, only while the drive is stopped
RO = "ro"  # read-only
RESERVED = "reserved"  # "Reservierter Parameter"
U16, S16, WORD = "U16", "S16", "WORD"


@dataclass(frozen=True)
class Parameter:
    """One row of a parameter table. A register holding several parameters
    (DB1/DC1 160, 164, 168) has one row per field, with its bits."""

    register: int
    number: str  # "P1-01", "P-36"
    name: str  # the manual's designation, as printed
    mode: str  # RUN, STOP, RO or RESERVED
    scaling: str  # "Skalierung" as printed, "" where none
    range: str  # "Wertebereich" as printed
    format: str  # U16, S16, WORD, "" where none is printed
    bits: tuple | None = None  # (first bit, last bit) of a field in a shared register

    @property
    def writable(self) -> bool:
        return self.mode in (RUN, STOP)

    @property
    def writable_in_run(self) -> bool:
        return self.mode == RUN

    @functools.cached_property  # the simulator asks every tick; the row never changes
    def scale(self) -> Scale | None:
        """The linear scale of the "Skalierung" cell, None where it is not one."""
        return Scale.parse(self.scaling)

    def _mask(self) -> tuple:
        first, last = self.bits if self.bits else (0, 15)
        return first, (1 << (last - first + 1)) - 1

    def extract(self, word: int) -> int:
        """This parameter's value in its register's word."""
        shift, mask = self._mask()
        return (word >> shift) & mask

    def insert(self, word: int, value: int) -> int:
        """The register word with this parameter set to value, the other
        fields kept (a read-modify-write of a shared register)."""
        shift, mask = self._mask()
        if not 0 <= value <= mask:
            raise ValueError(
                f"{self.number} {self.name}: {value} does not fit bits "
                f"{shift}..{shift + mask.bit_length() - 1} (0..{mask})"
            )
        return (word & ~(mask << shift) & 0xFFFF) | value << shift


HZ_60 = "3000 ≙ 50.0 Hz"  # every frequency parameter: PARAMETER_FREQUENCY
ONE = "1 ≙ 1"
_F_RANGE = "P1-02 (min: 0 Hz/0 rpm) - P1-01 (max: 500.0 Hz/30000 rpm)"
_FS_RAMP = "FS2, FS3: 1 ≙ 0.01 s FS4, ..., FS7: 1 ≙ 0.1 s"  # da1_ramp_scale

# Rows: (register or (register, first bit, last bit), number, name, mode,
# scaling, range, format), as printed; the comment is the manual line.

# DA1, Tabelle 20 (L1287-1525): register = group x 100 + index
_DA1_ROWS = (
    (101, "P1-01", "f-max", RUN, HZ_60, "P1-02 - (5 x P1-09) (max.: 500.0 Hz / 30000 rpm)", U16),  # L1287
    (102, "P1-02", "f-min", RUN, HZ_60, "0.0 Hz - P1-01", U16),  # L1288
    (103, "P1-03", "t-acc", RUN, "300 ≙ 30.0 s", "0.00 s - 6000 s", U16),  # L1289
    (104, "P1-04", "t-dec", RUN, "300 ≙ 30.0 s", "0.00 s - 6000 s", U16),  # L1290
    (105, "P1-05", "Stopp Modus", RUN, "", "0, 1, 2, 3, 4", U16),  # L1291
    (106, "P1-06", "Energieoptimierung", RUN, "", "0, 1", WORD),  # L1292
    (107, "P1-07", "Motor Nennspannung", STOP, "230 ≙ 230 V", "0 - U_e", U16),  # L1293
    (108, "P1-08", "Motor Nennstrom", STOP, "1 ≙ 0.1 A", "(0.1 - 1) x I_e", U16),  # L1294
    (109, "P1-09", "Motor Nennfrequenz", STOP, "500 ≙ 50 Hz", "10 Hz - 500 Hz", U16),  # L1295
    (110, "P1-10", "Motor Nenndrehzahl", RUN, "1500 ≙ 1500 rpm", "0 200 - 30000 rpm", U16),  # L1296
    (
        111,
        "P1-11",
        "U-Boost",
        STOP,  # L1297
        "-1 ≙ Auto 0 ≙ Disabled 1 ≙ 0.1 %",
        "0: Auto 0 - 30.0 % von P1-07",
        S16,
    ),
    (112, "P1-12", "Lokale Prozessdaten Quelle", STOP, "", "0 - 13", U16),  # L1298
    (113, "P1-13", "DI Konfiguration Auswahl", STOP, "", "0 - 21", U16),  # L1299
    (114, "P1-14", "Kennwort", RUN, "", "0 - 30000", U16),  # L1300
    (201, "P2-01", "f-Fix1", RUN, HZ_60, _F_RANGE, U16),  # L1301
    (202, "P2-02", "f-Fix2", RUN, HZ_60, _F_RANGE, U16),  # L1302
    (203, "P2-03", "f-Fix3", RUN, HZ_60, _F_RANGE, U16),  # L1303
    (204, "P2-04", "f-Fix4", RUN, HZ_60, _F_RANGE, U16),  # L1304
    (205, "P2-05", "f-Fix5", RUN, HZ_60, _F_RANGE, U16),  # L1305
    (206, "P2-06", "f-Fix6", RUN, HZ_60, _F_RANGE, U16),  # L1306
    (207, "P2-07", "f-Fix7", RUN, HZ_60, _F_RANGE, U16),  # L1307
    (208, "P2-08", "f-Fix8", RUN, HZ_60, _F_RANGE, U16),  # L1308
    (209, "P2-09", "f-Skip1", RUN, HZ_60, _F_RANGE, U16),  # L1316
    (210, "P2-10", "f-SkipBand1", RUN, HZ_60, _F_RANGE, U16),  # L1317
    (211, "P2-11", "ADO1 Funktion & Modus", RUN, "", "0, 1, ..., 11", U16),  # L1318
    (212, "P2-12", "A01 SignalFormat", RUN, "", "0, 1, ..., 5", U16),  # L1319
    (213, "P2-13", "ADO2 Funktion & Modus", RUN, "", "0, 1, ..., 11", U16),  # L1320
    (214, "P2-14", "A02 SignalFormat", RUN, "", "0, 1, ..., 5", U16),  # L1321
    (215, "P2-15", "RO1 Funktion", RUN, ONE, "0, ..., 7, 10, 11, 13", U16),  # L1322
    (216, "P2-16", "RO1 Obere Grenze", RUN, "1 ≙ 0.1 %", "P2-17 - 2000", U16),  # L1323
    (217, "P2-17", "RO1 Untere Grenze", RUN, "1 ≙ 0.1 %", "0.0 % - P2-16", U16),  # L1324
    (218, "P2-18", "RO2 Funktion", RUN, ONE, "0, ..., 7, 10, 11, 13", U16),  # L1325
    (219, "P2-19", "RO2 Obere Grenze", RUN, "1 ≙ 0.1 %", "P2-20 - 200 %", U16),  # L1326
    (220, "P2-20", "RO2 Untere Grenze", RUN, "1 ≙ 0.1 %", "0.0 % - P2-19", U16),  # L1327
    (221, "P2-21", "Anzeige Skalierung", RUN, "1 ≙ 0.001", "-30000 - +30000", U16),  # L1328
    (222, "P2-22", "Anzeige Quelle", RUN, "", "0, 1, 2, 3", U16),  # L1329
    (223, "P2-23", "t-n=0 Warten", RUN, "1 ≙ 0.1", "0.0 - 60.0 s", U16),  # L1330
    (224, "P2-24", "Schaltfrequenz", RUN, "", "0, 1, ..., 5", U16),  # L1331
    (225, "P2-25", "t-Schnellstopp", RUN, _FS_RAMP, "0.00 - 240 s", U16),  # L1332
    (226, "P2-26", "Motorfangschaltung Freigegeben", RUN, ONE, "0, 1, 2", WORD),  # L1333
    (227, "P2-27", "Standby Modus", RUN, "1 ≙ 0.01", "0.0 - 250 s", U16),  # L1334
    (228, "P2-28", "Slave Drehzahl-Skalierung", RUN, "", "0, 1, 2, 3", U16),  # L1335
    (229, "P2-29", "Slave Drehzahl-Skalierungsfaktor", RUN, "1 ≙ 0.1", "-500.0 - +500.0 %", S16),  # L1336
    (230, "P2-30", "A11 Signalbereich", RUN, "", "0, 1, ..., 7", U16),  # L1337
    (231, "P2-31", "A11 Gain", RUN, "1 ≙ 0.1", "0.0 - 2000.0 %", U16),  # L1338
    (232, "P2-32", "A11 Offset", RUN, "1 ≙ 0.1", "-500.0 - +500.0 %", S16),  # L1339
    (233, "P2-33", "A12 Signal Bereich", RUN, "", "0, 1, ..., 7", U16),  # L1340
    (234, "P2-34", "A12 Gain", RUN, "1 ≙ 0.1", "0.0 - 2000.0 %", U16),  # L1341
    (235, "P2-35", "A12 Offset", RUN, "1 ≙ 0.1", "-5000 - +5000", S16),  # L1342
    (236, "P2-36", "Start Modus", RUN, "", "0, 1, ..., 6", U16),  # L1343
    (237, "P2-37", "Digital Sollwert Reset Modus", RUN, "", "0, 1, ..., 7", U16),  # L1344
    (238, "P2-38", "Aktion@Netzausfall", RUN, "", "0, 1, 2, 3", U16),  # L1345
    (239, "P2-39", "Parametersperre", RUN, "", "0, 1", WORD),  # L1346
    (240, "P2-40", "Kennwort Level2", RUN, "", "0 - 9999", U16),  # L1347
    (301, "P3-01", "PID1 Kp", RUN, "1 ≙ 0.1", "1 - 300", U16),  # L1353
    (302, "P3-02", "PID1 Ti", RUN, "1 ≙ 0.1", "0 - 300 s", U16),  # L1354
    (303, "P3-03", "PID1 Kd", RUN, "1 ≙ 0.01", "0.00 - 100 s", U16),  # L1355
    (304, "P3-04", "PID1 Modus", RUN, "", "0, 1", WORD),  # L1356
    (305, "P3-05", "PID1 Sollwert 1 Quelle", RUN, ONE, "0, 1, 2", U16),  # L1357
    (306, "P3-06", "PID Sollwert Digital", RUN, "1 ≙ 0.1 %", "0 - 1000", U16),  # L1358
    (307, "P3-07", "PID1 Ausgang Obergrenze", RUN, "1 ≙ 0.1 %", "P3-08 - 1000", U16),  # L1359
    (308, "P3-08", "PID1 Ausgang Untergrenze", RUN, "1 ≙ 0.1 %", "0- P3-07", U16),  # L1360
    (309, "P3-09", "PID1 Ausgang GrenzeVorwahl", RUN, "", "0, 1, 2, 3", U16),  # L1361
    (310, "P3-10", "PID1 Istwert 1 Quelle", RUN, "", "0, 1", WORD),  # L1362
    (311, "P3-11", "PID1 Fehler Rampe", RUN, "1 ≙ 0.1 %", "0 - 250", U16),  # L1363
    (312, "P3-12", "PID1 Feedback 1 DispScale", RUN, "0: disabled 1 ≙ 0.001", "0.000 - 50.000", U16),  # L1364
    (313, "P3-13", "PID1 Aufweckschwelle", RUN, "1 ≙ 0.1 %", "0 - 1000", U16),  # L1365
    (314, "P3-14", "Reservierter Parameter", RESERVED, "", "", ""),  # L1366
    (315, "P3-15", "Reservierter Parameter", RESERVED, "", "", ""),  # L1367
    (316, "P3-16", "Reservierter Parameter", RESERVED, "", "", ""),  # L1368
    (317, "P3-17", "Reservierter Parameter", RESERVED, "", "", ""),  # L1369
    (318, "P3-18", "PID1 ResetControl", RUN, ONE, "0, 1", U16),  # L1370
    (401, "P4-01", "Steuerungsmodus", STOP, "", "0 - 6", U16),  # L1371
    (402, "P4-02", "Motor-Identifikation", STOP, "", "0, 1", WORD),  # L1372
    (403, "P4-03", "MSC Kp", RUN, "1 ≙ 0.1 %", "1 - 4000", U16),  # L1373
    (404, "P4-04", "MSC Ti", RUN, "1 ≙ 0.001 s", "1 - 1000", U16),  # L1374
    (405, "P4-05", "Motor CosPhi", RUN, "99 ≙ 0.99", "0,00 (= deaktiviert) 0,50 - 0,99", U16),  # L1375
    (406, "P4-06", "M-Soll Quelle", RUN, ONE, "0, 1, ..., 5", U16),  # L1376
    (407, "P4-07", "M-Max Motorbetrieb", RUN, "2000 ≙ 200.0 %", "0 - 2000", U16),  # L1377
    (408, "P4-08", "M-Min Motorbetrieb", RUN, "1 ≙ 0.1 %", "0 - 150 %", U16),  # L1378
    (409, "P4-09", "M-Max Generatorisch", RUN, "1 ≙ 1 %", "0 - 200 %", U16),  # L1379
    (410, "P4-10", "f-MidV/f", STOP, "1 ≙ 0.1 %", "0.0 - 100.0 %", U16),  # L1380
    (411, "P4-11", "V-MidV/f", RUN, "1 ≙ 0.1 %", "0.0 - 100.0 %", U16),  # L1381
    (412, "P4-12", "Thermischer Speicher Motor", RUN, ONE, "0, 1", U16),  # L1382
    (413, "P4-13", "Phasenfolge Motor drehen", RUN, ONE, "0, 1", U16),  # L1383
    (501, "P5-01", "PDP-Adresse", RUN, ONE, "1, 2, ..., 63", U16),  # L1391
    (502, "P5-02", "CAN0 Baudrate", RUN, "0 ≙ 125 kbps 1 ≙ 250 kbps", "0, 1, 2, 3", U16),  # L1392
    (503, "P5-03", "RS485-0 Baudrate", RUN, "0 ≙ 9.6 kbps 1 ≙ 19.2 kbps", "0, 1, 2, 3, 4", U16),  # L1393
    (504, "P5-04", "RS485-0 ParityType", RUN, "0 ≙ N-1 1 ≙ N-2", "0, 1, 2, 3", U16),  # L1394
    (505, "P5-05", "Modbus RTU0 COM Timeout", RUN, "1 ≙ 0.1 s", "0.0 - 5.0", U16),  # L1395
    (506, "P5-06", "Aktion@Modbus RTU Fehler", RUN, ONE, "0, 1, 2, 3", U16),  # L1396
    (507, "P5-07", "FieldbusRampControl", RUN, ONE, "0, 1", U16),  # L1397
    (508, "P5-08", "NETSendePZD4", RUN, ONE, "0, 1, ..., 7", U16),  # L1398
    (509, "P5-09", "Reservierter Parameter", RESERVED, "", "", U16),  # L1399
    (510, "P5-10", "Reservierter Parameter", RESERVED, "", "", U16),  # L1400
    (511, "P5-11", "Reservierter Parameter", RESERVED, "", "", U16),  # L1401
    (512, "P5-12", "NETSendePZD3", RUN, "", "0, 1, ..., 7", U16),  # L1402
    (513, "P5-13", "NETEmpfangsPZD4", RUN, "", "0, 1", U16),  # L1403
    (514, "P5-14", "NETEmpfangsPZD3", RUN, "", "0, 1, 2", U16),  # L1404
    (515, "P5-15", "ParameterAccess", RUN, ONE, "0, 1", U16),  # L1405
    (516, "P5-16", "Aktion@Kommunikationsverlust", RUN, ONE, "0, 1, 2, 3, 4", U16),  # L1406
    (517, "P5-17", "Modbus RTU0 Antwort Verzögerung", STOP, ONE, "0, 1, ..., 16", U16),  # L1407
    (601, "P6-01", "FirmwareUpgrade Freigegeben", STOP, ONE, "0, 1, 2, 3", U16),  # L1408
    (602, "P6-02", "Auto TemperaturManagement", RUN, ONE, "0, 1, ..., 5", WORD),  # L1409
    (603, "P6-03", "Auto Reset Verzögerung", RUN, ONE, "1 - 60", U16),  # L1410
    (604, "P6-04", "RO1 n-Hysterese", RUN, "1 ≙ 0.1 %", "0 - 250", U16),  # L1411
    (605, "P6-05", "Encoder Istwert Freigegeben", STOP, ONE, "0, 1", WORD),  # L1412
    (606, "P6-06", "Encoder PPR", STOP, "", "0 - 65535", U16),  # L1413
    (607, "P6-07", "Drehzahl Fehler Grenze", RUN, "1 ≙ 0.1 %", "0 - 500", U16),  # L1414
    (608, "P6-08", "Freq SollMax", RUN, "", "0, 5 - 20", U16),  # L1415
    (609, "P6-09", "DroopMax", RUN, "1 ≙ 0.1 %", "0 - 250", U16),  # L1416
    (610, "P6-10", "PLC Operation Freigegeben", RUN, ONE, "0, 1", WORD),  # L1417
    (611, "P6-11", "t-f-Fix vor Start", RUN, "1 ≙ 0.1 s", "0 - 2500", U16),  # L1418
    (612, "P6-12", "t-f-Fix nach Stopp", RUN, "1 ≙ 0.1 s", "0 - 2500", U16),  # L1419
    (613, "P6-13", "Bremse Lüften Verzögerung", RUN, "1 ≙ 0.1 s", "0 - 50", U16),  # L1420
    (614, "P6-14", "Bremse Schließen Verzögerung", RUN, "1 ≙ 0.1 s", "0 - 50", U16),  # L1421
    (615, "P6-15", "M vor Bremse Lüften", RUN, "1 ≙ 0.1 %", "0 - 2000", U16),  # L1422
    (616, "P6-16", "t vor Bremse Lüften", RUN, "1 ≙ 0.1 s", "0 - 250", U16),  # L1423
    (617, "P6-17", "Max Drehmoment Timeout", RUN, "1 ≙ 0.1 s", "0 - 250", U16),  # L1424
    (618, "P6-18", "DCBremseStrom", STOP, "0 ≙ Auto 1 ≙ 0.1 %", "0 : Auto 0 - 300", U16),  # L1430
    (619, "P6-19", "Bremswiderstand", RUN, ONE, "0 R_min - 200", U16),  # L1431
    (620, "P6-20", "P-Bremswiderstand", RUN, "1 ≙ 0.01 kW", "0 - 20000", U16),  # L1432
    (621, "P6-21", "Brake Chopper ED Heat-Up", RUN, "1 ≙ 0.1 %", "0 - 200", U16),  # L1433
    (622, "P6-22", "Reset Lüfterlaufzeit", RUN, ONE, "0, 1", WORD),  # L1434
    (623, "P6-23", "Reset kWh Zähler", RUN, ONE, "0, 1", WORD),  # L1435
    (624, "P6-24", "Service Intervall Zeit", RUN, ONE, "0 - 60 000 h (0 = disabled)", U16),  # L1436
    (625, "P6-25", "Reset ServiceAnzeige", RUN, ONE, "0 -1", WORD),  # L1437
    (626, "P6-26", "A01 Skalierung", RUN, "1 ≙ 0.1", "0 - 5000", U16),  # L1438
    (627, "P6-27", "A01 Offset", RUN, "1 ≙ 0.1 %", "-5000 - 5000", S16),  # L1439
    (628, "P6-28", "Zeiger auf Parameter", RUN, "", "0 - 127", U16),  # L1440
    (629, "P6-29", "Parameter Sichern", STOP, ONE, "0, 1", WORD),  # L1441
    (630, "P6-30", "Kennwort Level3", RUN, "", "0 - 9999", U16),  # L1442
    (701, "P7-01", "Motor Stator-Widerstand R1", RUN, "1 ≙ 0.001 Ω", "0.000 Ω - f (I_e)", U16),  # L1443
    (702, "P7-02", "Motor Rotor-Widerstand R2", RUN, "1 ≙ 0.001 Ω", "0.000 Ω - f (I_e)", U16),  # L1444
    (703, "P7-03", "Motor Stator Induktivität d-Achse", RUN, "1 ≙ 0.0001 H", "0.000 - 6.5535 H", U16),  # L1445
    (704, "P7-04", "Magnetisierungsstrom @M=0", RUN, "1 ≙ 0.1 A", "0.0 A - f (I_e)", U16),  # L1446
    (705, "P7-05", "Streuinduktivität Rel", RUN, "1 ≙ 0.001", "0.000 - 0.250", U16),  # L1447
    (706, "P7-06", "Motor Stator Induktivität q-Achse", RUN, "1 ≙ 0.0001 H", "0.000 - 6.5535 H", U16),  # L1448
    (707, "P7-07", "AnpassungGeneratorBetrieb", RUN, ONE, "0, 1", WORD),  # L1449
    (708, "P7-08", "ParameterAdaption", RUN, ONE, "0, 1", WORD),  # L1450
    (709, "P7-09", "Überspannung Stromgrenze", RUN, "1 ≙ 0.1 %", "0.0 - 100 % Motornennstrom", U16),  # L1451
    (710, "P7-10", "Trägheitsfaktor Last", RUN, ONE, "0 - 600", U16),  # L1452
    (711, "P7-11", "PWM untere Grenze", RUN, ONE, "0 - 500", U16),  # L1453
    (712, "P7-12", "t-Erregung-U/f", RUN, "", "0 - 2000", U16),  # L1454
    (713, "P7-13", "MSC Kd", RUN, "1 ≙ 0.1 %", "0 - 4000", U16),  # L1455
    (714, "P7-14", "Drehmomentanhebung", RUN, "1 ≙ 0.1 %", "0 - 1000", U16),  # L1456
    (715, "P7-15", "f-Drehmomentanhebung Grenze", RUN, "1 ≙ 0.1 %", "0 - 500", U16),  # L1457
    (716, "P7-16", "PM-MotorSignalIn", RUN, "", "0, 1, 2, 3", U16),  # L1458
    (717, "P7-17", "PM-MotorSignalInLevel", RUN, "", "0 - 100", U16),  # L1459
    (801, "P8-01", "t-acc2", RUN, _FS_RAMP, "0 - 60000", U16),  # L1467
    (802, "P8-02", "n-accMulti1", RUN, HZ_60, "0 - 30000", U16),  # L1468
    (803, "P8-03", "t-acc3", RUN, _FS_RAMP, "0 - 60000", U16),  # L1469
    (804, "P8-04", "n-accMulti2", RUN, HZ_60, "0 - 30000", U16),  # L1470
    (805, "P8-05", "t-acc4", RUN, _FS_RAMP, "0 - 60000", U16),  # L1471
    (806, "P8-06", "n-accMulti3", RUN, HZ_60, "0 - 30000", U16),  # L1472
    (807, "P8-07", "t-dec4", RUN, _FS_RAMP, "0 - 60000", U16),  # L1473
    (808, "P8-08", "n-decMulti3", RUN, HZ_60, "0 - 30000", U16),  # L1474
    (809, "P8-09", "t-dec3", RUN, _FS_RAMP, "0 - 60000", U16),  # L1475
    (810, "P8-10", "n-decMulti2", RUN, HZ_60, "0 - 30000", U16),  # L1476
    (811, "P8-11", "t-dec2", RUN, _FS_RAMP, "0 - 60000", U16),  # L1477
    (812, "P8-12", "n-decMulti1", RUN, HZ_60, "0 - 30000", U16),  # L1478
    (813, "P8-13", "Rampen Modus", RUN, ONE, "0, 1", WORD),  # L1479
    (901, "P9-01", "Betrieb Freigeben Quelle", STOP, ONE, "0 - 8", U16),  # L1480
    (902, "P9-02", "Stellstopp Quelle", STOP, ONE, "0 - 25", U16),  # L1481
    (903, "P9-03", "FWD Quelle", STOP, ONE, "0 - 25", U16),  # L1482
    (904, "P9-04", "REV Quelle", STOP, ONE, "0 - 25", U16),  # L1483
    (905, "P9-05", "Signalform", STOP, ONE, "0, 1", U16),  # L1484
    (906, "P9-06", "Erzwingen REV Quelle", STOP, ONE, "0 - 25", U16),  # L1485
    (907, "P9-07", "FehlerReset Quelle", STOP, ONE, "0 - 25", U16),  # L1486
    (908, "P9-08", "Externer Fehler1 Quelle", STOP, ONE, "0 - 25", U16),  # L1487
    (909, "P9-09", "LokalRemote @Einschalten", STOP, ONE, "0 - 25", U16),  # L1488
    (910, "P9-10", "Drehzahlquelle1", STOP, ONE, "0 - 16", U16),  # L1489
    (911, "P9-11", "Drehzahlquelle2", STOP, ONE, "0 - 16", U16),  # L1490
    (912, "P9-12", "Drehzahlquelle3", STOP, ONE, "0 - 16", U16),  # L1491
    (913, "P9-13", "Drehzahlquelle4", STOP, ONE, "0 - 16", U16),  # L1492
    (914, "P9-14", "Drehzahlquelle5", STOP, ONE, "0 - 16", U16),  # L1493
    (915, "P9-15", "Drehzahlquelle6", STOP, ONE, "0 - 16", U16),  # L1494
    (916, "P9-16", "Drehzahlquelle7", STOP, ONE, "0 - 16", U16),  # L1495
    (917, "P9-17", "Drehzahlquelle8", STOP, ONE, "0 - 16", U16),  # L1496
    (918, "P9-18", "Drehzahlauswahl B0", STOP, ONE, "0 - 25", U16),  # L1497
    (919, "P9-19", "Drehzahlauswahl B1", STOP, ONE, "0 - 25", U16),  # L1498
    (920, "P9-20", "Drehzahlauswahl B2", STOP, ONE, "0 - 25", U16),  # L1499
    (921, "P9-21", "f-Fix Auswahl B0", STOP, ONE, "0 - 25", U16),  # L1505
    (922, "P9-22", "f-Fix Auswahl B1", STOP, ONE, "0 - 25", U16),  # L1506
    (923, "P9-23", "f-Fix Auswahl B2", STOP, ONE, "0 - 25", U16),  # L1507
    (924, "P9-24", "t-acc Auswahl B0", STOP, ONE, "0 - 25", U16),  # L1508
    (925, "P9-25", "t-acc Auswahl B1", STOP, ONE, "0 - 25", U16),  # L1509
    (926, "P9-26", "t-dec Auswahl B0", STOP, ONE, "0 - 25", U16),  # L1510
    (927, "P9-27", "t-dec Auswahl B1", STOP, ONE, "0 - 25", U16),  # L1511
    (928, "P9-28", "digSollwert UP Quelle", STOP, ONE, "0 - 25", U16),  # L1512
    (929, "P9-29", "digSollwert DOWN Quelle", STOP, ONE, "0 - 25", U16),  # L1513
    (930, "P9-30", "Richtungsfreigabe FWD Quelle", STOP, ONE, "0 - 25", U16),  # L1514
    (931, "P9-31", "Richtungsfreigabe REV Quelle", STOP, ONE, "0 - 25", U16),  # L1515
    (932, "P9-32", "Reservierter Parameter", RESERVED, ONE, "", U16),  # L1516
    (933, "P9-33", "AD01 Funktions & Modus Erweiterung", STOP, ONE, "0, 1, 2", U16),  # L1517
    (934, "P9-34", "AD02 Funktions & Modus Erweiterung", STOP, ONE, "0, 1, 2", U16),  # L1518
    (935, "P9-35", "R01 Funktions Erweiterung", STOP, ONE, "0, 1", U16),  # L1519
    (936, "P9-36", "R02 Funktions Erweiterung", STOP, ONE, "0, 1", U16),  # L1520
    (937, "P9-37", "Anzeige Skalierung Quelle", STOP, ONE, "0, 1", U16),  # L1521
    (938, "P9-38", "PID1 Sollwert1 Quelle Ext", STOP, ONE, "0, 1", U16),  # L1522
    (939, "P9-39", "PID1 Istwert1 Quelle Ext", STOP, ONE, "0, 1", U16),  # L1523
    (940, "P9-40", "M-Ref Quelle Erweiterung", STOP, ONE, "0, 1", U16),  # L1524
    (941, "P9-41", "R05 Funktions Erweiterung", STOP, ONE, "0, 1", U16),  # L1525
)

# DB1, Tabelle 21 (L1631-1709). DC1's Tabelle 22 (L1780-1870) prints the
# same rows, a few in other words: P-02 "0.0 Hz - P-01", P-04 "0.00 s -
# 601 s" (a typo for 600 s), P-26/P-27 "3000 ≙ 50.0 Hz", P-32 low byte
# "t-DCBremse@Stopp", P-35 "100 ≙ 10.0 %"; none changes a register or a scale.
# The DB1 table has no P-52, P-53, P-57, P-58, P-69, P-70; neither has P-59.
_DB1_DC1_ROWS = (
    (129, "P-01", "f-max", RUN, HZ_60, "P-02 - (5 x P-09)", U16),  # L1631
    (130, "P-02", "f-min", RUN, HZ_60, "0 - P-01", U16),  # L1632
    (131, "P-03", "t-acc", RUN, "300 ≙ 3.00 s", "0.00 s - 600 s", U16),  # L1633
    (132, "P-04", "t-dec", RUN, "300 ≙ 3.00 s", "0.00 s - 600 s", U16),  # L1634
    (133, "P-05", "Stopp Modus", RUN, ONE, "0 - 3", U16),  # L1635
    (134, "P-06", "Energieoptimierung", RUN, ONE, "0 - 1", U16),  # L1636
    (135, "P-07", "Motor Nennspannung", STOP, "230 ≙ 230 V", "0 / 20 V - U_e", U16),  # L1637
    (136, "P-08", "Motor Nennstrom", RUN, "100 ≙ 10.0 A", "0.25 I_e - I_e", U16),  # L1638
    (137, "P-09", "Motor Nennfrequenz", STOP, "50 ≙ 50 Hz", "25 Hz - 500 Hz", U16),  # L1639
    (138, "P-10", "Motor Nenndrehzahl", RUN, ONE, "0 / 200 rpm - 30000 rpm", U16),  # L1640
    (
        139,
        "P-11",
        "U-Boost",
        RUN,  # L1646
        "100 ≙ 10.0 %",
        "0.0 % U_e - f (FS) FS1: 25 % U_e FS2: 20 % U_e FS3: 15 % U_e FS4: 10 % U_e",
        U16,
    ),
    (140, "P-12", "Lokale Prozessdaten Quelle", STOP, ONE, "0 - 13", U16),  # L1647
    (141, "P-13", "Letzter Fehler", RUN, ONE, "", U16),  # L1648
    (142, "P-14", "Kennwort", RUN, ONE, "0 - 65535", U16),  # L1649
    (143, "P-15", "DI Konfiguration Auswahl", STOP, ONE, "0-17", U16),  # L1650
    (144, "P-16", "AI1 Signal Bereich", RUN, ONE, "0 - 6", U16),  # L1651
    (145, "P-17", "Schaltfrequenz", RUN, ONE, "0 - f (I_e)", U16),  # L1652
    (146, "P-18", "RO1 Funktion", RUN, ONE, "0 - 7", U16),  # L1653
    (147, "P-19", "RO1 obere Grenze", RUN, "100 ≙ 10.0 %", "0 - 2", U16),  # L1654
    (148, "P-20", "f-Fix1", RUN, HZ_60, "f-min - f-max", U16),  # L1655
    (149, "P-21", "f-Fix2", RUN, HZ_60, "f-min - f-max", U16),  # L1656
    (150, "P-22", "f-Fix3", RUN, HZ_60, "f-min - f-max", U16),  # L1657
    (151, "P-23", "f-Fix4", RUN, HZ_60, "f-min - f-max", U16),  # L1658
    (152, "P-24", "t-Schnellstopp", RUN, "300 ≙ 3.00 s", "0.00 s - 600.0 s", U16),  # L1659
    (153, "P-25", "AO1 Funktion", RUN, ONE, "0 - 9", U16),  # L1660
    (154, "P-26", "f-SkipBand1", RUN, "3000 ≙ 50 Hz", "0.0 Hz - f-max", U16),  # L1661
    (155, "P-27", "f-Skip1", RUN, "3000 ≙ 50 Hz", "0.0 Hz - f-max", U16),  # L1662
    (156, "P-28", "U-MidU/f", STOP, "230 ≙ 230 V", "0 V - P-07", U16),  # L1663
    (157, "P-29", "f-MidU/f", STOP, HZ_60, "0 Hz - P-09", U16),  # L1664
    (158, "P-30", "Start Modus", RUN, ONE, "0 - 6", U16),  # L1665
    (159, "P-31", "Digital Sollwert Reset Modus", RUN, ONE, "0 - 3", U16),  # L1666
    ((160, 0, 7), "P-32", "t-DCBremse", RUN, "30 ≙ 3.0 s", "0.0 s - 25.0 s", U16),  # L1667
    ((160, 8, 15), "P-32", "DCBrake", RUN, ONE, "0-2", U16),  # L1668
    (161, "P-33", "Motorfangschaltung Freigeben", RUN, ONE, "0 - 1", U16),  # L1669
    (162, "P-34", "Bremschopper", RUN, ONE, "0 - 2", U16),  # L1670
    (163, "P-35", "AI1 Gain", RUN, "100 ≙ 10 %", "0 - 20", U16),  # L1671
    ((164, 0, 7), "P-36", "RS485-0 Adresse", RUN, ONE, "1 - 63", U16),  # L1672
    ((164, 8, 11), "P-36", "RS485-0 Baudrate", RUN, ONE, "0 - 6", U16),  # L1673
    ((164, 12, 15), "P-36", "Modbus RTU0 COM Timeout", RUN, ONE, "0 - 8", U16),  # L1681
    (165, "P-37", "Kennwort Level2", RUN, ONE, "0 - 9999", U16),  # L1682
    (166, "P-38", "Parametersperre", RUN, ONE, "0, 1", U16),  # L1683
    (167, "P-39", "AI1 Offset", RUN, "10 ≙ 1.0 %", "-5 - +5", U16),  # L1684
    ((168, 0, 13), "P-40", "Anzeige Skalierung", RUN, "10000 ≙ 10.000", "0 - 16.000", U16),  # L1685
    ((168, 14, 15), "P-40", "Anzeige Skalierung Quelle", RUN, ONE, "0 - 2", U16),  # L1686
    (169, "P-41", "PID1 Kp", RUN, "10 ≙ 1.0", "0,1 - 30", U16),  # L1687
    (170, "P-42", "PID1 Ti", RUN, "300 ≙ 3.00 s", "0.0 s - 30.0 s", U16),  # L1688
    (171, "P-43", "PID1 Modus", RUN, ONE, "0 - 1", U16),  # L1689
    (172, "P-44", "PID1 Sollwert 1 Quelle", RUN, ONE, "0 - 1", U16),  # L1690
    (173, "P-45", "PID1 Sollwert Digital", RUN, ONE, "0 - 1", U16),  # L1691
    (174, "P-46", "PID1 Istwert 1 Quelle", RUN, ONE, "0 - 3", U16),  # L1692
    (175, "P-47", "AI2 Signal Bereich", RUN, ONE, "0 - 6", U16),  # L1693
    (176, "P-48", "t-Standby", RUN, "300 ≙ 3.00 s", "0.0 s - 25.0 s", U16),  # L1694
    (177, "P-49", "PID1 Aufweckschwelle", RUN, ONE, "0 - 1", U16),  # L1695
    (178, "P-50", "CAN0 Baudrate", RUN, ONE, "0 - 3", U16),  # L1696
    (179, "P-51", "Thermischer Speicher Motor", RUN, ONE, "0 - 1", U16),  # L1697
    (182, "P-54", "RO1 Hysterese", RUN, ONE, "0 - 1", U16),  # L1698
    (183, "P-55", "RO1 Einschaltverzögerung", RUN, "300 ≙ 3.00 s", "0.0 s - 250.0 s", U16),  # L1699
    (184, "P-56", "Modbus Parity Type", RUN, "", "", U16),  # L1700
    (188, "P-60", "Steuerungsmodus", RUN, ONE, "0 - 4", U16),  # L1701
    (189, "P-61", "Motor-Identifikation", STOP, "300 ≙ 3.00 s", "0.0 s - 250.0 s", U16),  # L1702
    (190, "P-62", "MSC Verstärkung", RUN, "10 ≙ 1.0 %", "0.0 % - 200.0 %", U16),  # L1703
    (191, "P-63", "I-Stromgrenze", RUN, "10 ≙ 1.0 %", "0.1 % - 175 %", U16),  # L1704
    (192, "P-64", "Motor Stator Widerstand R1", RUN, "", "0.00 Ω - 655.35 Ω", U16),  # L1705
    (193, "P-65", "Motor Stator Induktivität d-Achse", RUN, "", "0.0 mH - 6553.5 mH", U16),  # L1706
    (194, "P-66", "Motor Stator Induktivität q-Achse", RUN, "", "0.0 mH - 6553.5 mH", U16),  # L1707
    (195, "P-67", "f-DCBremse@Stopp", RUN, HZ_60, "0.0 Hz - P-01", U16),  # L1708
    (196, "P-68", "DC-Bremse Strom", RUN, "10 ≙ 1.0 %", "0,0 % - 100.0 %", U16),  # L1709
)
_DC1_ONLY_ROWS = (
    (180, "P-52", "ParameterAccess", RUN, ONE, "0 - 1", U16),  # L1847
    (181, "P-53", "Aktion@Kommunikationsverlust", RUN, ONE, "0 - 4", U16),  # L1848
    (185, "P-57", "TCP Enable Service", RUN, "", "", U16),  # L1852
    (186, "P-58", "TCP0 Security Timeout", RUN, "", "", U16),  # L1853
    (197, "P-69", "LocalControl Logic1", RUN, "", "", U16),  # L1869
    (198, "P-70", "LocalControl Logic2", RUN, "", "", U16),  # L1870
)

# DE1, Tabelle 23 (L1905-1957). P-01/P-02 are STOP-only here but RUN on
# DB1/DC1; the DE1 communication table heads a "RUN, STOP" column and prints
# RUN everywhere (A33). The printed parameter range "129 - 169" ends before
# P-42 .. P-48 (A15).
_DE1_ROWS = (
    (129, "P-01", "f-max", STOP, HZ_60, "P-02 - 300 Hz", U16),  # L1905
    (130, "P-02", "f-min", STOP, HZ_60, "0 - P-01", U16),  # L1906
    (131, "P-03", "t-acc", RUN, "300 ≙ 3.00 s", "0.1 - 300 s", U16),  # L1907
    (132, "P-04", "t-dec", RUN, "300 ≙ 3.00 s", "0.1 - 300 s", U16),  # L1908
    (133, "P-05", "Stopp Modus", RUN, ONE, "0, 1", U16),  # L1909
    (134, "P-06", "Energieoptimierung", STOP, ONE, "0, 1", U16),  # L1910
    (135, "P-07", "Motor Nennspannung", STOP, "230 ≙ 230 V", "50 - 500 V", U16),  # L1911
    (136, "P-08", "Motor Nennstrom", STOP, "100 ≙ 10.0 A", "(10 - 100 %) x I_e", U16),  # L1912
    (137, "P-09", "Motor Nennfrequenz", STOP, "50 ≙ 50 Hz", "20 - 300 Hz", U16),  # L1913
    (138, "P-10", "Motor Nenndrehzahl", STOP, ONE, "0 200 - 15000 rpm", U16),  # L1914
    (139, "P-11", "U-Boost", RUN, "100 ≙ 10.0 %", "0.0 - 40.0 %", U16),  # L1915
    (140, "P-12", "Lokale Prozessdaten Quelle", RUN, ONE, "0 - 13", U16),  # L1921
    (141, "P-13", "Letzter Fehler", RO, "", "", U16),  # L1922
    (142, "P-14", "Kennwort", RUN, ONE, "0 - 65535", U16),  # L1923
    (143, "P-15", "DI Konfiguration Auswahl", STOP, ONE, "0 - 9", U16),  # L1924
    (144, "P-16", "AI1 Signal Bereich", STOP, ONE, "0- 3", U16),  # L1925
    (145, "P-17", "AI1 Gain", RUN, "10 ≙ 1", "0.10 - 2.500", U16),  # L1926
    (146, "P-18", "AI1 Invertieren", STOP, ONE, "0, 1", U16),  # L1927
    (147, "P-19", "DI3 Logik", STOP, ONE, "0, 1", U16),  # L1928
    (148, "P-20", "f-Fix1", STOP, HZ_60, "P-02 – P-01", U16),  # L1929
    (149, "P-21", "f-Fix2", STOP, HZ_60, "P-02 – P-01", U16),  # L1930
    (150, "P-22", "f-Fix3", STOP, HZ_60, "P-02 – P-01", U16),  # L1931
    (151, "P-23", "f-Fix4", STOP, HZ_60, "P-02 – P-01", U16),  # L1932
    (152, "P-24", "Digital Sollwert Reset Modus", RUN, ONE, "0, 1, 2, 3", U16),  # L1933
    (153, "P-25", "DCBremse", STOP, ONE, "0, 1, 2, 3", U16),  # L1934
    (154, "P-26", "t-DCBremse@Stop", RUN, "100 ≙ 10.0 s", "0 - 10 s", U16),  # L1935
    (155, "P-27", "DCBremseSpannung", RUN, "100 ≙ 10 %", "0 - P-07", U16),  # L1936
    (156, "P-28", "f-DCBremse@Stop", RUN, "3000 ≙ 50 Hz", "0 - P-01", U16),  # L1937
    (157, "P-29", "Schaltfrequenz", STOP, ONE, "0, 1, ..., 5", U16),  # L1938
    (158, "P-30", "Start Modus", STOP, ONE, "0, 1, ..., 10", U16),  # L1939
    (159, "P-31", "Überspannungs-Kontrolle", RUN, ONE, "0, 1", U16),  # L1940
    (160, "P-32", "Auto Temperatur-Management", STOP, ONE, "0, 1", U16),  # L1941
    (161, "P-33", "Thermischer Speicher Motor", STOP, ONE, "0, 1", U16),  # L1942
    (162, "P-34", "PDP-Address", RUN, ONE, "1 - 63", U16),  # L1943
    (163, "P-35", "RS485-0 Baudrate", RUN, ONE, "0, 1, 2, 3, 4", U16),  # L1944
    (164, "P-36", "Modbus RTU0 COM Timeout", RUN, ONE, "0, 1, ..., 8", U16),  # L1945
    (165, "P-37", "Parametertz", STOP, ONE, "0, 1", U16),  # L1946
    (166, "P-38", "Kennwort Level2", RUN, ONE, "0 - 9999", U16),  # L1947
    (167, "P-39", "Parameter sperre", RUN, ONE, "0, 1", U16),  # L1948
    (168, "P-40", "Aktion@Kommunikationsverlust", RUN, ONE, "0, 1, 2, 3, 4", U16),  # L1949
    (169, "P-41", "ParameterAccess", RUN, ONE, "0, 1", U16),  # L1950
    (170, "P-42", "f-SkipBand1", RUN, "", "", U16),  # L1951
    (171, "P-43", "f-Skip1", RUN, "", "", U16),  # L1952
    (172, "P-44", "AI1 Offset", RUN, "", "", U16),  # L1953
    (173, "P-45", "FireMode Functionality", RUN, "", "", U16),  # L1954
    (174, "P-46", "Motor-Identifikation", RUN, "", "", U16),  # L1955
    (175, "P-47", "Modbus Adresse", RUN, "", "", U16),  # L1956
    (176, "P-48", "Modbus Communication Data Format", RUN, "1", "", U16),  # L1957
)

# DE11 in addition, Tabelle 24 (L1968-1974). P-57 and P-58 sit at 183 and
# 184, not at 128 + n = 185/186 as on the DC1 (A16); the table is followed.
_DE11_ROWS = (
    (178, "P-50", "CANO Baudrate", RUN, "", "0, 1, 2, 3", U16),  # L1968
    (179, "P-51", "R01 Funktion", RUN, "", "0, 1, ..., 9", U16),  # L1969
    (180, "P-52", "R01 Obere Grenze", RUN, "", "0.0 - 200.0 %", U16),  # L1970
    (181, "P-53", "R01 Hysterese", RUN, "", "0.0 - 100.0 %", U16),  # L1971
    (182, "P-54", "R01 Einschaltverzögerung", RUN, "", "0.0 - 250.0 s", U16),  # L1972
    (183, "P-57", "TCP Enable Service", RUN, "", "0...7", U16),  # L1973
    (184, "P-58", "TCP0 Security Timeout", RUN, "", "0...60", U16),  # L1974
)


def _build(rows) -> tuple:
    params = []
    for register, number, name, mode, scaling, value_range, fmt in rows:
        bits = None
        if isinstance(register, tuple):
            register, first, last = register
            bits = (first, last)
        params.append(Parameter(register, number, name, mode, scaling, value_range, fmt, bits))
    return tuple(params)


PARAMETERS = {
    Family.DA1: _build(_DA1_ROWS),
    Family.DB1: _build(_DB1_DC1_ROWS),
    Family.DC1: _build(sorted(_DB1_DC1_ROWS + _DC1_ONLY_ROWS, key=lambda row: row[1])),
    Family.DE1: _build(_DE1_ROWS),
}
DE11_PARAMETERS = _build(_DE11_ROWS)

# Where a table contradicts the 128 + n rule (A16)
DE11_REGISTER_EXCEPTIONS = {"P-57": 183, "P-58": 184}

_DA1_NUMBER = re.compile(r"^P(\d)-(\d{1,2})$")
_COMPACT_NUMBER = re.compile(r"^P-(\d{1,2})$")


def parameter_rows(family: Family, number: str, *, de11: bool = False) -> tuple:
    """The table rows of a parameter number (more than one for the fields of
    a shared register, e.g. DB1/DC1 P-36). ValueError if the manual has none."""
    return _rows(family, number.strip().upper(), de11)


@functools.cache  # the tables never change; the simulator asks every tick
def _rows(family: Family, number: str, de11: bool) -> tuple:
    tables = PARAMETERS[family] + (DE11_PARAMETERS if family is Family.DE1 and de11 else ())
    rows = tuple(p for p in tables if p.number == number)
    if not rows:
        model = "DE11" if family is Family.DE1 and de11 else family.name
        raise ValueError(f"{number} is not in the {model} parameter table")
    return rows


def da1_parameter_register(group: int, index: int) -> int:
    """The register of DA1 parameter P<group>-<index>: group x 100 + index
    (every row of Tabelle 20 follows it, digest §3.5). ValueError for a number
    the table does not have; the P0 display values have their own registers
    (monitor_registers)."""
    if group == 0:
        raise ValueError(
            f"P0-{index:02d} is a display value, not in the group x 100 + index scheme: see monitor_registers"
        )
    parameter_rows(Family.DA1, f"P{group}-{index:02d}")
    return group * 100 + index


def compact_parameter_register(family: Family, n: int, *, de11: bool = False) -> int:
    """The register of P-<n> on a DB1, DC1 or DE1: 128 + n (digest §3.5),
    except DE11 P-57/P-58 (A16). ValueError for a number the family's table
    does not have."""
    if family is Family.DA1:
        raise ValueError(f"the DA1 numbers its parameters P<group>-<index>, it has no P-{n:02d}")
    number = f"P-{n:02d}"
    parameter_rows(family, number, de11=de11)
    if family is Family.DE1 and de11 and number in DE11_REGISTER_EXCEPTIONS:
        return DE11_REGISTER_EXCEPTIONS[number]
    return 128 + n


def parameter_register(family: Family, number: str, *, de11: bool = False) -> int:
    """The Modbus register of a parameter named as on the drive: DA1 "P1-01"
    -> 101, DC1 "P-36" -> 164. ValueError for a number of the wrong form for
    the family, or one the manual's table does not have."""
    text = number.strip().upper()
    if family is Family.DA1:
        match = _DA1_NUMBER.match(text)
        if not match:
            raise ValueError(f"DA1 parameters are named P<group>-<index> (P1-01), not {number!r}")
        return da1_parameter_register(int(match.group(1)), int(match.group(2)))
    match = _COMPACT_NUMBER.match(text)
    if not match:
        raise ValueError(f"{family.name} parameters are named P-<n> (P-01), not {number!r}")
    return compact_parameter_register(family, int(match.group(1)), de11=de11)


# Parameters the runtime names: the command source and the bus ramp switch
CONTROL_SOURCE_PARAMETER = {Family.DA1: "P1-12", Family.DB1: "P-12", Family.DC1: "P-12", Family.DE1: "P-12"}
# Values of that parameter that take commands and setpoint from Modbus:
# DA1 4 "Steuerung über Feldbus" (Modbus RTU unless a fieldbus option is
# fitted, L376); DB1/DC1 3 Modbus, 4 Modbus with ramp times from Modbus
# (L397, L413); DE1 3 (L436). The parameter is STOP-only on DA1, DB1, DC1.
MODBUS_CONTROL_SOURCES = {Family.DA1: (4,), Family.DB1: (3, 4), Family.DC1: (3, 4), Family.DE1: (3,)}
# ID 4 ramp time counts only when ramps come from the bus: DA1 P5-07
# FieldbusRampControl = 1 (L389), DB1/DC1 P-12 = 4. The DE1 has no ID 4.
DA1_FIELDBUS_RAMP_CONTROL = "P5-07"
DB1_DC1_MODBUS_RAMPS_SOURCE = 4
