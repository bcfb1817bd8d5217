import subprocess,sys,re,collections
sys.path.insert(0,'/tmp/m')
def norm(n):
    n=re.sub(r'\s*\[.*\]$','',n); n=re.sub(r'^\S*?:','',n,count=1) if re.match(r'^\S+\.(rs|c|h|S):',n) else n
    n=re.sub(r'<impl [^>]*>','',n)
    n=re.sub(r'^(tirecontact_core|tirecontact_report|tirecontact_io|tirecontact)::','',n)
    return n
def load(f):
    out=subprocess.run(['callgrind_annotate','--threshold=100','--show-percs=no','--auto=no',f],capture_output=True,text=True).stdout
    d=collections.Counter()
    for line in out.splitlines():
        m=re.match(r'\s*([\d,]+)\s+(\S.*)',line)
        if m and ('::' in m.group(2) or '???' in m.group(2) or '.c:' in m.group(2) or '.S:' in m.group(2)):
            d[norm(m.group(2))]+=int(m.group(1).replace(',',''))
    return d
a=load(sys.argv[1]); b=load(sys.argv[2])
for k in sorted(set(a)|set(b),key=lambda k:-abs(a.get(k,0)-b.get(k,0)))[:30]:
    print(f"{a.get(k,0)/1e6:9.2f} {b.get(k,0)/1e6:9.2f} {(a.get(k,0)-b.get(k,0))/1e6:+9.2f}  {k[:130]}")
