# softplc in a container: the embedded default plant, in real time, forever
# (README "Running as a service").
#
#   docker build -t softplc .
#   docker run --rm softplc                                   # the default plant; Ctrl-C stops it cleanly
#   docker run --rm softplc softplc run --duration 30s        # or for a while
#   docker run --rm -p 5020:5020 -v "$PWD/plant:/plant:ro" softplc softplc run /plant/plant.toml
#
# The servers listen on 127.0.0.1 unless their section says otherwise, and
# 127.0.0.1 inside a container is reachable from nowhere else: a plant that
# serves HMIs sets host = "0.0.0.0" in [web], [opcua] and [modbus_server]
# (softplc logs a warning that the PLC is then reachable from the network)
# and is started with -p for each port. SIGTERM (docker stop) stops the scan,
# puts the outputs in their safe values and saves retained data.
FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 PYTHONUNBUFFERED=1 PIP_NO_CACHE_DIR=1 PIP_DISABLE_PIP_VERSION_CHECK=1

COPY . /src
RUN pip install /src && rm -rf /src \
    && useradd --system --create-home --home-dir /var/lib/softplc softplc

USER softplc
WORKDIR /var/lib/softplc

# [web] 8080, [opcua] 4840, [modbus_server] 5020 (the defaults of runtime/config/servers.py)
EXPOSE 8080 4840 5020
STOPSIGNAL SIGTERM
CMD ["softplc", "run"]
