"""Configuration snippets the [[modbus]] configuration tests share."""

RTU = '[[modbus]]\nname = "drives"\ntransport = "rtu"\ndevice = "sim"\n'
TCP = '[[modbus]]\nname = "gateway"\ntransport = "tcp"\n'
CH = "modbus[0].channel[0]"  # the first channel's key in messages
READ = '[[modbus.channel]]\nunit = 1\nfunction = 3\noffset = 5\ncount = 5\nread_to = "%IW200"\n'
DA1 = '[[sim]]\ntype = "da1"\nunit = 1\n'
ONLY_CAN = "only for a CAN device (ltmr, fc280, mpu2s); a Modbus device has modbus and unit"


def channel(function, body: str = "", unit: int = 1, offset: int = 0) -> str:
    return f"[[modbus.channel]]\nunit = {unit}\nfunction = {function}\noffset = {offset}\n{body}"
