// Reads a KTX2 file with the independent ktx-parse package and prints its facts as JSON
// (tests/unit/test_container.cpp compares them with texproc's reader).
import { read } from 'ktx-parse';
import { readFileSync } from 'fs';
const c = read(new Uint8Array(readFileSync(process.argv[2])));
const d = c.dataFormatDescriptor[0];
console.log(JSON.stringify({vkFormat: c.vkFormat, typeSize: c.typeSize, width: c.pixelWidth, height: c.pixelHeight,
  layers: c.layerCount, faces: c.faceCount, levels: c.levels.length, levelBytes: c.levels.map(l => l.levelData.byteLength),
  colorModel: d.colorModel, transfer: d.transferFunction, primaries: d.colorPrimaries, bytesPlane0: d.bytesPlane[0],
  samples: d.samples.length, writer: c.keyValue.KTXwriter}));
